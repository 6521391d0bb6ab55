#pragma once
/// @file
/// Options of the wheel-odometry velocity factor (wheel_velocity_factor.h), apart from it so
/// that configuration code does not pull in Ceres.

#include "swlio/core/config_issue.h"
#include "swlio/estimator/common/estimator_config.h"

namespace swlio::estimator {

struct WheelFactorConfig {
  /// Off by default: only a chassis that reports odometry on CAN has it (daemon `can:`).
  bool enabled = false;
  /// The chassis base frame (x forward, z up; the point whose speed the wheels report, midway
  /// between the driven wheels) in the IMU frame; identity by default.
  ExtrinsicConfig T_imu_base;
  /// Standard deviations of the base velocity: forward (the wheels' speed: noise, radius error
  /// and slip), lateral and vertical (the non-holonomic constraint: a wheeled base does not
  /// slide sideways; vertical also absorbs bumps and suspension travel). Forward is loose: a
  /// wheel-radius error biases every frame's speed the same way, ten frames a second (loop943
  /// seed 1 with the simulator's 0.4 % radius error, without loop closure: APE 0.716 m without
  /// wheels, 0.857 m at σ 0.05, 0.543 m at σ 0.2).
  double sigma_forward_mps = 0.2;
  double sigma_lateral_mps = 0.05;
  double sigma_vertical_mps = 0.1;
  /// A frame takes the measurement interpolated at its time from samples at most this far from
  /// it (the nearest one held when the next has not arrived yet); none: no factor.
  double max_gap_s = 0.05;
  /// Slip gate: a measurement further than this from the predicted forward speed is dropped.
  double max_innovation_mps = 0.5;

  ConfigIssues Validate() const;
};

}  // namespace swlio::estimator

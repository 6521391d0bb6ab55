#pragma once
/// @file
/// Chassis wheel odometry of a differential-drive base, as the chassis reports it on CAN: the
/// rim speeds of the left and right wheels in one frame (the default layout of the `can:` block
/// of config/swlio.yaml: id 0x201, DLC 8, left int16 Intel at byte 0, right at byte 2, 0.001 m/s
/// per LSB), 50 Hz, received by the host 1–3 ms after the wheels were read.
///
/// Base frame: x forward, y left, z up, its origin on the ground midway between the wheels;
/// `T_imu_base` places it in the IMU frame. The true base velocity (base axes) and yaw rate:
///   v_base = R_ibᵀ (R_wiᵀ v_world_imu + ω_imu × p_ib),   ω_base = R_ibᵀ ω_imu
/// and the rim speeds of a track width b:  v_l = v_x − ω_z·b/2,  v_r = v_x + ω_z·b/2.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <ostream>
#include <vector>

#include "scenarios/trajectory.h"
#include "swlio/drivers/can_config.h"
#include "swlio/drivers/can_frame.h"

namespace swlio::sim {

/// What the chassis adds to the true rim speeds, per wheel:
///   measured = (1 + scale_error) · true + white noise, quantized to `quantum_mps`.
struct WheelNoiseModel {
  /// Wheel radius error (worn or under-inflated tyre): σ of the per-wheel scale error drawn
  /// once per seed (sim_setup.cpp). Assumed.
  double scale_error_sigma = 0.005;
  double scale_error_left = 0.0;   ///< the drawn value (truth, written to the manifest)
  double scale_error_right = 0.0;  ///< the drawn value
  double speed_sigma_mps = 0.01;   ///< white noise per wheel and sample (encoder jitter). Assumed.
  double quantum_mps = 0.001;      ///< one LSB of the int16 signal
  double latency_min_s = 0.001;    ///< host receive time − time the wheels were read:
  double latency_max_s = 0.003;    ///< uniform in [min, max] (CAN + driver). Assumed.
};

struct WheelSimConfig {
  bool enabled = true;  ///< can.log in recordings (--no-wheel: off)
  /// The base frame in the IMU frame. Set in sim_setup.cpp: directly below the IMU, on the
  /// ground (the route's imu_height_m).
  Eigen::Isometry3d T_imu_base = Eigen::Isometry3d::Identity();
  double track_width_m = 0.5;
  double rate_hz = 50.0;
  uint32_t can_id = 0x201;  ///< standard 11-bit identifier
  double scale_mps_per_lsb = 0.001;
  WheelNoiseModel noise;
};

/// One wheel-odometry frame with its truth.
struct SimWheelSample {
  int64_t t_true_ns = 0;  ///< sim time at which the wheels were read
  int64_t t_rx_ns = 0;    ///< sim time at which the host received the frame
  Eigen::Vector3d v_base_mps = Eigen::Vector3d::Zero();  ///< true base velocity, base axes
  double yaw_rate_radps = 0.0;                           ///< true ω_z of the base
  double left_mps = 0.0;   ///< rim speed as sent (noise, scale error, quantization)
  double right_mps = 0.0;  ///< rim speed as sent
  drivers::CanFrame frame;
};

struct BaseTwist {
  Eigen::Vector3d v_base_mps = Eigen::Vector3d::Zero();        ///< base origin, base axes
  Eigen::Vector3d omega_base_radps = Eigen::Vector3d::Zero();  ///< base axes
};

/// The base's true velocity and rate from the IMU's kinematics (formula in the file comment).
BaseTwist TrueBaseTwist(const Kinematics& imu, const Eigen::Isometry3d& T_imu_base);

/// The CAN layout the frames use, as the daemon's `can:` configuration (mode wheel_speeds,
/// unit mps); `enabled` set, interface "can0".
drivers::CanConfig WheelCanConfig(const WheelSimConfig& config);

/// One frame carrying the two rim speeds (rounded to the LSB, saturated to int16).
drivers::CanFrame EncodeWheelFrame(const WheelSimConfig& config, double left_mps, double right_mps);

/// Frames over [0, duration], in receive order; deterministic for a seed.
std::vector<SimWheelSample> SimulateWheels(const Trajectory& trajectory,
                                           const WheelSimConfig& config,
                                           uint64_t seed);

/// Writes the frames as a candump log (drivers/candump_log.h, as swliod --record writes
/// can.log) stamped with host receive times `host_start_ns + t_rx_ns`. False on a write error.
bool WriteCanLog(const std::vector<SimWheelSample>& samples,
                 int64_t host_start_ns,
                 std::ostream& out);

/// wheel_truth.csv: `t_ns,v_x_mps,yaw_rate_radps` (host time of the reading, true base values).
bool WriteWheelTruth(const std::vector<SimWheelSample>& samples,
                     int64_t host_start_ns,
                     std::ostream& out);

}  // namespace swlio::sim

#pragma once
/// @file
/// Configuration of the LiDAR-inertial estimator. Plain structs with documented defaults;
/// loaded by the daemon, validated here.

#include <Eigen/Geometry>
#include <array>
#include <string>

#include "swlio/core/config_issue.h"

namespace swlio::estimator {

/// Continuous-time IMU noise model (the units are those of the datasheets).
/// Defaults: Xsens MTi-G-710 (MTi 100-series) datasheet noise densities, gyro 0.01 °/s/√Hz and
/// accelerometer 60 µg/√Hz; the bias random walks are inflated over the datasheet's in-run
/// stability to cover temperature and vibration on a robot.
struct ImuNoiseConfig {
  double acc_noise_density_mps2_per_sqrthz = 60e-6 * 9.80665;
  double gyro_noise_density_radps_per_sqrthz = 0.01 * 3.14159265358979323846 / 180.0;
  double acc_bias_random_walk_mps3_per_sqrthz = 1e-4;
  double gyro_bias_random_walk_radps2_per_sqrthz = 1e-5;

  ConfigIssues Validate() const;
};

/// A rigid transform `T_a_b` (maps frame-b points into frame a) as the configuration writes it:
/// the extrinsic `T_imu_lidar`, the wheel base `T_imu_base`. The numbers are kept as given, so a
/// printed configuration states them exactly. Rotation R = Rz(yaw)·Ry(pitch)·Rx(roll).
struct ExtrinsicConfig {
  std::array<double, 3> translation_m = {0.0, 0.0, 0.0};  ///< origin of frame b in frame a
  std::array<double, 3> rotation_rpy_deg = {0.0, 0.0, 0.0};

  ConfigIssues Validate() const;
  /// The transform these numbers describe.
  Eigen::Isometry3d ToIsometry() const;
  /// The numbers of `T`: ToIsometry() gives `T` back to rounding (not always to the last bit).
  static ExtrinsicConfig FromIsometry(const Eigen::Isometry3d& T);
};

struct EstimatorConfig {
  /// "tightly-coupled" (default) or "lidar-only" (the baseline: IMU for prediction/de-skew only).
  std::string mode = "tightly-coupled";
  ImuNoiseConfig imu_noise;
  ExtrinsicConfig extrinsic_imu_lidar;
  double gravity_mps2 = 9.80665;
  /// The robot must stand still this long before the static initialization completes.
  double init_static_duration_s = 1.0;
  /// MakeOdometryConfig (lidar_odometry.h) gives these three to the front end and the maps.
  double plane_voxel_m = 0.4;        ///< down-sampling of planar features
  double edge_voxel_m = 0.2;         ///< down-sampling of edge features
  double local_map_radius_m = 80.0;  ///< local map kept around the robot
  /// The IMU-rate output (odom → base_link) never jumps: each newly optimized state's
  /// correction is taken in at these rates (imu_rate_propagator.h; 0 and 0: at once).
  double output_rebase_rate_mps = 0.1;
  double output_rebase_rate_radps = 0.05;

  ConfigIssues Validate() const;
};

}  // namespace swlio::estimator

#pragma once
/// @file
/// Core sample and state types shared by drivers, estimator, ipc and daemon.
///
/// Frames: `T_a_b` maps points from frame b to frame a, so `T_a_c = T_a_b * T_b_c`.
/// World: gravity-aligned (z up), origin at the first IMU pose after initialization.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace swlio {

/// One inertial measurement in the IMU frame: the means of the specific force and of the
/// angular rate over the interval since the previous sample, stamped at the interval's end.
/// That is what an Xsens MTi outputs as Acceleration and RateOfTurn (dv/Δt and dq/Δt of its
/// strapdown integration: MTi Family Reference Manual MT1600P §4.3, "calibrated data has been
/// going through strapdown integration and inverse strapdown integration"; Xsens DOT User
/// Manual §4.2.1, "calibrated acceleration = dv/dt"), and it keeps motion faster than the
/// output rate (chassis vibration) in the integrals. Instantaneous samples are turned into such
/// means by `ImuIntervalMeans` (estimator/imu/imu_interval_means.h).
struct ImuSample {
  int64_t t_ns = 0;  ///< host time (CLOCK_MONOTONIC ns) of the interval's end
  Eigen::Vector3d acc_mps2 = Eigen::Vector3d::Zero();    ///< mean specific force, m/s²
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();  ///< mean angular rate, rad/s
};

/// One LiDAR return in the LiDAR frame of its scan.
struct LidarPoint {
  Eigen::Vector3f xyz_m = Eigen::Vector3f::Zero();  ///< position, metres, LiDAR frame
  float intensity = 0.0f;                           ///< reflectivity as reported (0–255)
  uint16_t ring = 0;                                ///< laser channel, 0 = lowest elevation
  int64_t dt_ns = 0;  ///< time of this firing after the scan's `t_start_ns`, ≥ 0
};

/// One LiDAR sweep. Every point carries its own time: `t_start_ns + dt_ns`.
/// Convention (stated once): a scan's time is its first firing, `t_start_ns`; `t_end_ns` is
/// its last firing. Both are host time.
struct Scan {
  int64_t t_start_ns = 0;
  int64_t t_end_ns = 0;
  uint64_t seq = 0;      ///< scan counter from the assembler
  bool partial = false;  ///< true when packets are missing or the sweep is incomplete
  std::vector<LidarPoint> points;
};

/// One wheel-odometry measurement of the chassis (base) frame: x forward, z up.
struct WheelOdometry {
  int64_t t_ns = 0;                  ///< host time
  double linear_velocity_mps = 0.0;  ///< forward speed
  double yaw_rate_radps = 0.0;       ///< about the base z axis, counter-clockwise positive
};

/// One GNSS position fix of the antenna (WGS-84), with the receiver's own accuracy estimate.
struct GnssFix {
  int64_t t_ns = 0;  ///< host time of the fix
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double height_m = 0.0;  ///< above the WGS-84 ellipsoid
  double h_acc_m = 0.0;   ///< horizontal accuracy estimate (1σ-like, as the receiver reports)
  double v_acc_m = 0.0;   ///< vertical accuracy estimate
  uint8_t fix_type = 0;   ///< u-blox NAV-PVT fixType: 0 none, 2 2D, 3 3D, 4 GNSS+DR, 5 time
  uint8_t num_sv = 0;     ///< satellites used
};

/// Navigation state of the IMU body frame.
struct State {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
  Eigen::Vector3d vel_world = Eigen::Vector3d::Zero();  ///< m/s, world frame
  Eigen::Vector3d bias_acc = Eigen::Vector3d::Zero();   ///< m/s², IMU frame
  Eigen::Vector3d bias_gyro = Eigen::Vector3d::Zero();  ///< rad/s, IMU frame
};

}  // namespace swlio

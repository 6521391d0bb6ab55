#pragma once
/// @file
/// LiDAR–IMU extrinsic calibration from a stretch of LiDAR-only odometry and the IMU, in one
/// batch (in the spirit of LI-Init: Zhu, Zheng, Yuan, Liu, Zhang, "Robust Real-time LiDAR-inertial
/// Initialization", IROS 2022; our own formulation and code).
///
/// Why not in the window: the window's local map is built with the extrinsic being estimated
/// (T_world_imu · T_imu_lidar), which anchors the estimate to its own past value
/// (docs/notes/2026-11-22-online-extrinsic.md). LiDAR-only odometry builds its map at LiDAR
/// poses, so its poses T_w0_lidar do not depend on the extrinsic.
///
/// Unknowns: per pose k the IMU pose T_world_imu,k and [v, b_a, b_g]_k; the extrinsic
/// T_imu_lidar; the tilt of the odometry world, T_world_w0 = Rot(Exp([a, b, 0])) · T̄_world_w0
/// (T̄ from DynamicInitializer; its yaw and origin fix the gauge). Residuals:
///  - the LiDAR pose: T_world_w0 · T_w0_lidar,k against T_world_imu,k · T_imu_lidar, as the
///    error in the measured pose's tangent, weighted by what the registration determined (its
///    Hessian) and under a Cauchy loss;
///  - IMU pre-integration between consecutive poses (ImuFactor, paper eq. 21), with the bias
///    random walk;
///  - weak priors: the extrinsic about the guess, b_a about zero on the first pose.
/// Solved twice with Ceres, re-integrating at the new biases in between. The extrinsic's
/// covariance is reported: on a planar drive (rotation about one axis only) the translation
/// along that axis is not observable and stays at its prior.
/// Pure library: no clocks, no printing.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <string>

#include "swlio/core/types.h"
#include "swlio/estimator/common/estimator_config.h"
#include "swlio/estimator/init/dynamic_initializer.h"

namespace swlio::estimator {

struct ExtrinsicCalibratorOptions {
  /// LiDAR-only odometry pose noise per pose (1σ).
  double position_sigma_m = 0.02;
  double rotation_sigma_rad = 0.2 * 3.14159265358979323846 / 180.0;
  /// With a pose's registration Hessian H (StampedLidarPose::hessian): the pose's covariance
  /// σ_point² H⁻¹ plus a floor, so that a direction the scan hardly constrains (along a road
  /// between walls) weighs little; 0 ignores H. σ_point is the RS-LiDAR-16's ±2 cm range
  /// accuracy (RoboSense RS-LiDAR-16 user manual, specifications); on the `calibration` drive
  /// 0.02 m did better than 0.05 m (docs/notes/2026-12-02-calibration-scenario.md).
  double hessian_point_sigma_m = 0.02;
  double hessian_floor_position_m = 0.002;
  double hessian_floor_rotation_rad = 0.02 * 3.14159265358979323846 / 180.0;
  /// Cauchy loss on each whitened pose residual from the second solve on, after every pose's σ
  /// was scaled so that the median whitened squared norm is χ²(6)'s: a sweep the registration
  /// got wrong (in a fast turn over a cable cover, up to 5 cm off) gets bounded influence. The
  /// reported covariance is the Gaussian one at that solution.
  double pose_cauchy_scale = 0.5;
  /// Prior about the guessed extrinsic.
  double extrinsic_prior_sigma_m = 0.1;
  double extrinsic_prior_sigma_rad = 0.1;
  double acc_bias_prior_sigma_mps2 = 0.05;
  int max_iterations = 30;  ///< per solve
  /// The translation moves from the guess only along directions the motion determined (σ at
  /// most this): on a planar drive the lever arm along the turn axis keeps the guess. This and
  /// max_rotation_sigma_rad test the covariance before the correlation_poses factor.
  double max_translation_sigma_m = 0.03;
  /// Not ok when the rotation's largest standard deviation exceeds this (too little turning).
  double max_rotation_sigma_rad = 0.3 * 3.14159265358979323846 / 180.0;
  /// The initial alignment (gravity, velocities, biases) before the joint solve.
  DynamicInitializer::Options alignment;
};

struct ExtrinsicCalibration {
  std::string message;  ///< why not ok
  /// The calibrated extrinsic when ok, else the guess.
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  /// Over the tangent of pose_manifold.h: [δp (IMU frame, m); δφ (LiDAR frame, rad)]; the
  /// Gaussian covariance at the solution times correlation_poses.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Vector3d bias_gyro = Eigen::Vector3d::Zero();  ///< at the last pose
  Eigen::Vector3d bias_acc = Eigen::Vector3d::Zero();
  int translation_directions = 0;  ///< of the 3, moved from the guess (max_translation_sigma_m)
  /// The factor on every pose's nominal σ (Hessian-based or position_sigma_m) that the first
  /// solve's residuals asked for (see pose_cauchy_scale); ≫ 1: the odometry is worse than
  /// its Hessians say.
  double pose_sigma_scale = 1.0;
  /// The pose residuals' autocorrelation time (poses, ≥ 1); `covariance` is scaled by it.
  double correlation_poses = 1.0;
  double position_rms_m = 0.0;  ///< LiDAR pose residuals after the solve
  double rotation_rms_rad = 0.0;
  int iterations = 0;
  bool ok = false;
};

/// Poses time-ordered (≥ alignment.min_frames), the IMU samples spanning them.
ExtrinsicCalibration CalibrateExtrinsic(const EstimatorConfig& config,
                                        std::span<const StampedLidarPose> poses,
                                        std::span<const ImuSample> imu,
                                        const Eigen::Isometry3d& T_imu_lidar_guess,
                                        const ExtrinsicCalibratorOptions& options = {});

}  // namespace swlio::estimator

#pragma once
/// @file
/// The uncertainty of an estimated state as the outputs state it.
///
/// The window optimizes T_world_imu with the tangent [δp; δφ] of pose_manifold.h (δp in world
/// axes, δφ a right perturbation in the IMU frame: R ← R Exp(δφ)) and [v_world, b_a, b_g]
/// additively. Consumers (ROS 2's PoseWithCovariance, the health output) expect the rotation
/// error about the fixed world axes, R ← Exp(δθ) R: δθ = R δφ. So the 15×15 state covariance
/// reported is, in this order,
///   [δp_world (m), δθ_world (rad), δv_world (m/s), δb_a (m/s²), δb_g (rad/s)],
/// P = J C Jᵀ with J = blockdiag(I, R, I, I, I) and C the covariance in the optimizer's tangent.

#include <Eigen/Core>

namespace swlio::estimator {

inline constexpr int kStateCovSize = 15;
inline constexpr int kCovPos = 0;        ///< δp_world
inline constexpr int kCovRot = 3;        ///< δθ_world
inline constexpr int kCovVel = 6;        ///< δv_world
inline constexpr int kCovBiasAcc = 9;    ///< δb_a
inline constexpr int kCovBiasGyro = 12;  ///< δb_g

using StateCovarianceMatrix = Eigen::Matrix<double, kStateCovSize, kStateCovSize>;

struct StateCovariance {
  StateCovarianceMatrix P = StateCovarianceMatrix::Zero();  ///< order as in the file comment
  /// Covariance of the attitude against gravity, Q·R (GravityAttitudeCovariance), about the
  /// gravity-aligned axes: what the IMU observes of the tilt. Without an estimated map tilt
  /// (Q = I) it is P's rotation block.
  Eigen::Matrix3d rot_gravity = Eigen::Matrix3d::Zero();
  bool valid = false;  ///< false when it could not be computed (no solve, rank-deficient)
};

/// C in the optimizer's tangent [δp; δφ (body); δv; δb_a; δb_g] → P in world rotation axes.
StateCovarianceMatrix ToWorldRotationAxes(const StateCovarianceMatrix& C_tangent,
                                          const Eigen::Matrix3d& R_world_imu);

/// Joint covariance of the map's tilt θ (2, additive; Q = Exp([θx, θy, 0]) rotates map vectors
/// into the gravity-aligned frame, gravity_tilt_imu_factor.h) and the frame's rotation tangent δφ
/// (R ← R Exp(δφ)) → covariance of the attitude against gravity, Q·R, about the gravity-aligned
/// axes. First order: Exp([θ + δθ; 0]) ≈ Exp(J_l [δθ; 0]) Q and Q Exp(R δφ) = Exp(Q R δφ) Q, so
/// δθ_g = J_l(θ)[:, 0:2] δθ + Q R δφ.
Eigen::Matrix3d GravityAttitudeCovariance(const Eigen::Matrix2d& C_tilt,
                                          const Eigen::Matrix<double, 2, 3>& C_tilt_phi,
                                          const Eigen::Matrix3d& C_phi,
                                          const Eigen::Vector2d& tilt_rad,
                                          const Eigen::Matrix3d& R_map_imu);

/// Covariance of the velocity in the IMU frame, v_imu = Rᵀ v_world, from P (first order:
/// δv_imu = Rᵀ δv_world + [v_imu]× Rᵀ δθ_world). This is the frame of ROS 2's Odometry twist.
Eigen::Matrix3d VelocityImuCovariance(const StateCovarianceMatrix& P,
                                      const Eigen::Matrix3d& R_world_imu,
                                      const Eigen::Vector3d& vel_world_mps);

}  // namespace swlio::estimator

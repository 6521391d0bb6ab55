#pragma once
/// @file
/// State prediction from pre-integrated IMU terms and the pre-integration residual with its
/// analytic Jacobians (Forster et al., TRO 2017, eq. (44)–(45)); the Ceres factor wraps these.
///
/// World frame: z up, gravity_world = (0, 0, −g). Rotations R = R_world_imu.
///
/// Perturbations for the Jacobians (stated once; a Ceres manifold must match them):
///   R ← R Exp(δφ)   (right, in the IMU frame)
///   p ← p + δp      (additive, world frame — differs from Forster's p + R δp)
///   v ← v + δv      (additive, world frame)
///   b_g ← b_g + δb_g,  b_a ← b_a + δb_a
/// Residual rows [r_ΔR; r_Δv; r_Δp], the order of PreintegratedImu::covariance.

#include <Eigen/Core>

#include "swlio/core/types.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {

using Mat93 = Eigen::Matrix<double, 9, 3>;

/// Gravity vector in the world frame (z up).
inline Eigen::Vector3d GravityWorld(double gravity_mps2) { return {0.0, 0.0, -gravity_mps2}; }

/// One navigation state in the form the residual takes.
struct NavPoint {
  Eigen::Matrix3d R_world_imu = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();
};

inline NavPoint ToNavPoint(const State& s) {
  return {s.T_world_imu.linear(), s.T_world_imu.translation(), s.vel_world};
}

/// Jacobians of the 9-dimensional residual, one 9×3 block per perturbation.
struct ImuResidualJacobians {
  Mat93 R_i, p_i, v_i, R_j, p_j, v_j, bias_gyro, bias_acc;
};

/// The state at the interval end from the state at its start (eq. (44) with the start's
/// biases, then the navigation equations):
///   R_j = R_i ΔR,  v_j = v_i + g Δt + R_i Δv,  p_j = p_i + v_i Δt + ½ g Δt² + R_i Δp.
/// Biases are carried over; t_ns advances by Δt.
State PredictState(const State& start,
                   const PreintegratedImu& pim,
                   const Eigen::Vector3d& gravity_world);

/// Residual (eq. (45)) with the terms corrected to the biases (bias_gyro, bias_acc) by eq. (44):
///   r_ΔR = Log(ΔR(b)ᵀ R_iᵀ R_j)
///   r_Δv = R_iᵀ (v_j − v_i − g Δt) − Δv(b)
///   r_Δp = R_iᵀ (p_j − p_i − v_i Δt − ½ g Δt²) − Δp(b)
/// Fills `jacobians` when not null.
Vec9 ImuResidual(const PreintegratedImu& pim,
                 const NavPoint& state_i,
                 const NavPoint& state_j,
                 const Eigen::Vector3d& bias_gyro,
                 const Eigen::Vector3d& bias_acc,
                 const Eigen::Vector3d& gravity_world,
                 ImuResidualJacobians* jacobians = nullptr);

/// Convenience: the biases are those of state_i.
Vec9 ImuResidual(const PreintegratedImu& pim,
                 const State& state_i,
                 const State& state_j,
                 const Eigen::Vector3d& gravity_world,
                 ImuResidualJacobians* jacobians = nullptr);

}  // namespace swlio::estimator

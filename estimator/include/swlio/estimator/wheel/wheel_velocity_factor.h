#pragma once
/// @file
/// Wheel-odometry velocity factor of the window (issue 8): the chassis' measured forward speed
/// v_m, with the non-holonomic constraint of a wheeled base (no sideways or vertical speed), on
/// one frame's state. With T_imu_base = (R_ib, p_ib) (the base frame, x forward, z up, in the
/// IMU frame), the frame's T_world_imu = (R, p), velocity v and gyro bias b_g, and the gyro rate
/// ω_m measured at the frame's time:
///
///   ω     = ω_m − b_g                                   (IMU angular rate)
///   v_b   = R_ibᵀ (Rᵀ v + ω × p_ib)                     (the base origin's velocity, base axes)
///   r     = S (v_b − [v_m, 0, 0])                       (S = diag(1/σ_forward, 1/σ_lateral,
///                                                                 1/σ_vertical))
///
/// Jacobians in the tangents (pose_manifold.h: R ← R Exp(δφ)):
///   ∂r/∂δφ = S R_ibᵀ [Rᵀ v]×,   ∂r/∂δp = 0,   ∂r/∂v = S R_ibᵀ Rᵀ,   ∂r/∂b_g = S R_ibᵀ [p_ib]×
/// (Exp(δφ)ᵀ Rᵀ v ≈ Rᵀ v − δφ × Rᵀ v = Rᵀ v + [Rᵀ v]× δφ;  −(b_g × p_ib) = p_ib × b_g).
/// The measured yaw rate is not used: the gyro measures it better.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>

#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_factor.h"

namespace swlio::estimator {

struct WheelFactorNoise {
  double forward_mps = 0.05;
  double lateral_mps = 0.05;
  double vertical_mps = 0.1;
};

class WheelVelocityFactor final : public ceres::SizedCostFunction<3, kPoseSize, kSpeedBiasSize> {
 public:
  /// Null when a value is not finite or a σ is not positive.
  static std::unique_ptr<WheelVelocityFactor> Create(double forward_speed_mps,
                                                     const Eigen::Vector3d& gyro_radps,
                                                     const Eigen::Isometry3d& T_imu_base,
                                                     const WheelFactorNoise& noise);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  /// The base velocity (base axes) the state implies (v_b above).
  Eigen::Vector3d BaseVelocity(const double* pose, const double* speed_bias) const;
  double forward_speed_mps() const { return v_m_; }

 private:
  WheelVelocityFactor(double forward_speed_mps,
                      const Eigen::Vector3d& gyro_radps,
                      const Eigen::Isometry3d& T_imu_base,
                      const WheelFactorNoise& noise);

  const double v_m_;
  const Eigen::Vector3d gyro_radps_;
  const Eigen::Matrix3d R_base_imu_;  ///< R_ibᵀ
  const Eigen::Vector3d p_imu_base_;
  const Eigen::Vector3d sqrt_info_;  ///< diagonal of S
};

}  // namespace swlio::estimator

// Wheel-odometry velocity factor: the maths is in wheel_velocity_factor.h.

#include "swlio/estimator/wheel/wheel_velocity_factor.h"

#include "swlio/core/lie.h"

namespace swlio::estimator {

std::unique_ptr<WheelVelocityFactor> WheelVelocityFactor::Create(
    double forward_speed_mps,
    const Eigen::Vector3d& gyro_radps,
    const Eigen::Isometry3d& T_imu_base,
    const WheelFactorNoise& noise) {
  const bool finite =
      std::isfinite(forward_speed_mps) && gyro_radps.allFinite() && T_imu_base.matrix().allFinite();
  const bool positive =
      noise.forward_mps > 0.0 && noise.lateral_mps > 0.0 && noise.vertical_mps > 0.0;
  if (!finite || !positive) return nullptr;
  return std::unique_ptr<WheelVelocityFactor>(
      new WheelVelocityFactor(forward_speed_mps, gyro_radps, T_imu_base, noise));
}

WheelVelocityFactor::WheelVelocityFactor(double forward_speed_mps,
                                         const Eigen::Vector3d& gyro_radps,
                                         const Eigen::Isometry3d& T_imu_base,
                                         const WheelFactorNoise& noise)
    : v_m_(forward_speed_mps),
      gyro_radps_(gyro_radps),
      R_base_imu_(T_imu_base.linear().transpose()),
      p_imu_base_(T_imu_base.translation()),
      sqrt_info_(1.0 / noise.forward_mps, 1.0 / noise.lateral_mps, 1.0 / noise.vertical_mps) {}

Eigen::Vector3d WheelVelocityFactor::BaseVelocity(const double* pose,
                                                  const double* speed_bias) const {
  const Eigen::Matrix3d R = PoseFromParameters(pose).linear();
  const Eigen::Map<const Eigen::Vector3d> v(speed_bias + kSbVel);
  const Eigen::Map<const Eigen::Vector3d> b_g(speed_bias + kSbBiasGyro);
  const Eigen::Vector3d omega = gyro_radps_ - b_g;
  return R_base_imu_ * (R.transpose() * v + omega.cross(p_imu_base_));
}

bool WheelVelocityFactor::Evaluate(double const* const* parameters,
                                   double* residuals,
                                   double** jacobians) const {
  const double* pose = parameters[0];
  const double* sb = parameters[1];
  const Eigen::Vector3d v_b = BaseVelocity(pose, sb);
  const Eigen::DiagonalMatrix<double, 3> S(sqrt_info_);
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = S * (v_b - Eigen::Vector3d(v_m_, 0.0, 0.0));
  if (jacobians == nullptr) return true;
  const Eigen::Matrix3d R = PoseFromParameters(pose).linear();
  const Eigen::Map<const Eigen::Vector3d> v(sb + kSbVel);
  if (jacobians[0] != nullptr) {
    Eigen::Matrix<double, 3, kPoseTangentSize> J_delta = Eigen::Matrix<double, 3, 6>::Zero();
    J_delta.rightCols<3>() = S * (R_base_imu_ * lie::Hat(R.transpose() * v));
    Eigen::Map<Eigen::Matrix<double, 3, kPoseSize, Eigen::RowMajor>> J(jacobians[0]);
    J = J_delta * PoseMinusJacobianAt(pose);
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, kSpeedBiasSize, Eigen::RowMajor>> J(jacobians[1]);
    J.setZero();
    J.middleCols<3>(kSbVel) = S * (R_base_imu_ * R.transpose());
    J.middleCols<3>(kSbBiasGyro) = S * (R_base_imu_ * lie::Hat(p_imu_base_));
  }
  return true;
}

}  // namespace swlio::estimator

#include "swlio/estimator/window/standstill.h"

#include <Eigen/Core>
#include <cmath>

#include "swlio/estimator/imu/imu_moments.h"

namespace swlio::estimator {

ConfigIssues StandstillConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "max_acc_std_mps2", max_acc_std_mps2, 0.0, 1.0);
  CheckInRange(issues, "max_gyro_std_radps", max_gyro_std_radps, 0.0, 0.5);
  CheckInRange(issues, "max_specific_force_error_mps2", max_specific_force_error_mps2, 0.0, 1.0);
  CheckInRange(issues, "max_rate_radps", max_rate_radps, 0.0, 0.5);
  CheckInRange(issues, "max_lidar_speed_mps", max_lidar_speed_mps, 0.0, 1.0);
  CheckInRange(issues, "sigma_velocity_mps", sigma_velocity_mps, 1e-4, 1.0);
  return issues;
}

bool ImuAtRest(const std::vector<ImuSample>& samples,
               const Eigen::Matrix3d& R_gravity_imu,
               const Eigen::Vector3d& bias_acc,
               const Eigen::Vector3d& bias_gyro,
               double gravity_mps2,
               const StandstillConfig& config) {
  if (samples.size() < 4) return false;
  const ImuMoments f = ComputeImuMoments(samples, [](const ImuSample& s) { return s.acc_mps2; });
  const ImuMoments w = ComputeImuMoments(samples, [](const ImuSample& s) { return s.gyro_radps; });
  const Eigen::Vector3d f_rest =
      R_gravity_imu.transpose() * Eigen::Vector3d(0.0, 0.0, gravity_mps2) + bias_acc;
  return f.std.maxCoeff() <= config.max_acc_std_mps2 &&
         w.std.maxCoeff() <= config.max_gyro_std_radps &&
         (f.mean - f_rest).norm() <= config.max_specific_force_error_mps2 &&
         (w.mean - bias_gyro).norm() <= config.max_rate_radps;
}

bool ZeroVelocityFactor::Evaluate(double const* const* parameters,
                                  double* residuals,
                                  double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> v(parameters[0] + kSbVel);
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = inv_sigma_ * v;
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, kSpeedBiasSize, Eigen::RowMajor>> J(jacobians[0]);
    J.setZero();
    J.block<3, 3>(0, kSbVel) = inv_sigma_ * Eigen::Matrix3d::Identity();
  }
  return true;
}

}  // namespace swlio::estimator

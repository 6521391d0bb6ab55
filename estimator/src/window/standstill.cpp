#include "swlio/estimator/window/standstill.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "swlio/estimator/imu/imu_stillness.h"

namespace swlio::estimator {

ConfigIssues StandstillConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "imu_window_s", imu_window_s, 0.0, 5.0);
  CheckInRange(issues, "max_acc_std_mps2", max_acc_std_mps2, 0.0, 1.0);
  CheckInRange(issues, "max_gyro_std_radps", max_gyro_std_radps, 0.0, 0.5);
  CheckInRange(issues, "max_specific_force_error_mps2", max_specific_force_error_mps2, 0.0, 1.0);
  CheckInRange(issues, "max_rate_radps", max_rate_radps, 0.0, 0.5);
  CheckInRange(issues, "max_lidar_speed_mps", max_lidar_speed_mps, 0.0, 1.0);
  CheckInRange(issues, "sigma_velocity_mps", sigma_velocity_mps, 1e-4, 1.0);
  return issues;
}

std::optional<double> ImuAtRest(const std::vector<ImuSample>& samples,
                                const Eigen::Matrix3d& R_gravity_imu,
                                const Eigen::Vector3d& bias_acc,
                                const Eigen::Vector3d& bias_gyro,
                                double gravity_mps2,
                                const StandstillConfig& config) {
  if (samples.size() < 4) return std::nullopt;
  const ImuStillness still = ComputeImuStillness(samples);
  const Eigen::Vector3d f_rest =
      R_gravity_imu.transpose() * Eigen::Vector3d(0.0, 0.0, gravity_mps2) + bias_acc;
  const bool at_rest =
      still.acc_lowpass_std_mps2 <= config.max_acc_std_mps2 &&
      still.gyro_lowpass_std_radps <= config.max_gyro_std_radps &&
      (still.acc_mean_mps2 - f_rest).norm() <= config.max_specific_force_error_mps2 &&
      (still.gyro_mean_radps - bias_gyro).norm() <= config.max_rate_radps;
  if (!at_rest) return std::nullopt;
  // Per axis: the RMS over all three axes spread evenly.
  return std::max(config.sigma_velocity_mps, still.velocity_rms_mps / std::sqrt(3.0));
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

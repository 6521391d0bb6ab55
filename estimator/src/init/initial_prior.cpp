#include "swlio/estimator/init/initial_prior.h"

#include "swlio/core/lie.h"

namespace swlio::estimator {

Eigen::Matrix<double, 15, 15> InitialCovariance(const Eigen::Matrix3d& R_world_imu,
                                                double gravity_mps2,
                                                const InitialStdDevs& sigma) {
  // x = A z, z = [δp, δψ, n/g, δv, δb_a, δb_g] standard normal (16).
  const Eigen::Vector3d u = R_world_imu.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d U = lie::Hat(u);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 15, 16> A = Eigen::Matrix<double, 15, 16>::Zero();
  A.block<3, 3>(0, 0) = sigma.position_m * I;
  A.block<3, 1>(3, 3) = sigma.yaw_rad * u;
  A.block<3, 3>(3, 4) = -sigma.tilt_measured_rad * U;
  A.block<3, 3>(6, 7) = sigma.velocity_mps * I;
  A.block<3, 3>(3, 10) = (sigma.bias_acc_mps2 / gravity_mps2) * U;
  A.block<3, 3>(9, 10) = sigma.bias_acc_mps2 * I;
  A.block<3, 3>(12, 13) = sigma.bias_gyro_radps * I;
  return A * A.transpose();
}

}  // namespace swlio::estimator

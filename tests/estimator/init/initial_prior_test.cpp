// The first state's covariance keeps the accelerometer's reading of gravity certain while the
// tilt is only as certain as the accelerometer bias.

#include "swlio/estimator/init/initial_prior.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

constexpr double kG = 9.81;

Eigen::Matrix3d Tilted() {
  return (Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(-0.05, Eigen::Vector3d::UnitY()))
      .matrix();
}

TEST(InitialPrior, GravityReadingIsCertainTiltFollowsTheBias) {
  const Eigen::Matrix3d R = Tilted();
  InitialStdDevs s;
  s.tilt_measured_rad = 1e-4;
  s.bias_acc_mps2 = 0.05;
  s.yaw_rad = 2e-3;
  const Eigen::Matrix<double, 15, 15> S = InitialCovariance(R, kG, s);
  EXPECT_TRUE(S.llt().info() == Eigen::Success) << "positive definite";

  // δf = g [u]× δφ + δb_a (the specific force read at rest).
  const Eigen::Vector3d u = R.transpose() * Eigen::Vector3d::UnitZ();
  Eigen::Matrix<double, 3, 15> J = Eigen::Matrix<double, 3, 15>::Zero();
  J.block<3, 3>(0, 3) = kG * lie::Hat(u);
  J.block<3, 3>(0, 9) = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S_f = J * S * J.transpose();
  // Across u: only the measurement noise, n = g·1e-4; along u: the bias prior.
  const Eigen::Matrix3d P_perp = Eigen::Matrix3d::Identity() - u * u.transpose();
  EXPECT_NEAR((P_perp * S_f * P_perp).trace(), 2 * std::pow(kG * 1e-4, 2), 1e-9);
  EXPECT_NEAR(u.dot(S_f * u), std::pow(0.05, 2), 1e-9);

  // Each tilt axis: σ² = (n/g)² + (σ_ba/g)²; the yaw (about u): its own σ.
  const Eigen::Matrix3d S_phi = S.block<3, 3>(3, 3);
  const Eigen::Vector3d across = u.unitOrthogonal();
  EXPECT_NEAR(across.dot(S_phi * across), 1e-8 + std::pow(0.05 / kG, 2), 1e-12);
  EXPECT_NEAR(u.dot(S_phi * u), 4e-6, 1e-12);
  // Position, velocity and gyro bias independent of the rest.
  EXPECT_NEAR(S(0, 0), 1e-6, 1e-15);
  EXPECT_EQ((S.block<3, 12>(0, 3).norm()), 0.0);
  EXPECT_EQ((S.block<3, 6>(12, 3).norm()), 0.0);
}

}  // namespace
}  // namespace swlio::estimator

// The reported covariance's frames: the optimizer's body-frame rotation tangent becomes
// rotation about the world axes, and the velocity covariance in the IMU frame follows v_imu.

#include "swlio/estimator/state_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

Eigen::Matrix3d Yaw(double rad) {
  return Eigen::AngleAxisd(rad, Eigen::Vector3d::UnitZ()).matrix();
}

TEST(StateCovariance, BodyRollOfAYawedRobotIsRotationAboutTheWorldY) {
  StateCovarianceMatrix C = StateCovarianceMatrix::Identity() * 1e-6;
  C(kCovRot, kCovRot) = 1e-2;  // body x (roll) uncertain
  const StateCovarianceMatrix P = ToWorldRotationAxes(C, Yaw(M_PI / 2));
  // Facing +y, the body x axis is the world y axis.
  EXPECT_NEAR(P(kCovRot + 1, kCovRot + 1), 1e-2, 1e-12);
  EXPECT_NEAR(P(kCovRot, kCovRot), 1e-6, 1e-12);
  // Position, velocity and biases are untouched.
  EXPECT_TRUE((P.topLeftCorner<3, 3>().isApprox(C.topLeftCorner<3, 3>())));
  EXPECT_TRUE((P.bottomRightCorner<9, 9>().isApprox(C.bottomRightCorner<9, 9>())));
}

// Monte Carlo: sample the state error in the optimizer's tangent, apply it as the optimizer
// does (R ← R Exp(δφ), v ← v + δv), and compare the sample covariance of the world-axes
// rotation error and of v_imu with the first-order formulas.
TEST(StateCovariance, MatchesSampledErrors) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  Eigen::Matrix<double, kStateCovSize, kStateCovSize> A;
  for (int i = 0; i < A.size(); ++i) A.data()[i] = n01(rng);
  const StateCovarianceMatrix C = 1e-4 * (A * A.transpose() / kStateCovSize);
  const Eigen::Matrix3d R =
      Yaw(0.7) * Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 1, 0).normalized()).matrix();
  const Eigen::Vector3d v_world(1.5, -0.4, 0.1);
  const StateCovarianceMatrix P = ToWorldRotationAxes(C, R);
  const Eigen::Matrix3d P_v_imu = VelocityImuCovariance(P, R, v_world);

  const Eigen::LLT<StateCovarianceMatrix> llt(C);
  const int n = 200000;
  Eigen::Matrix3d S_rot = Eigen::Matrix3d::Zero(), S_v = Eigen::Matrix3d::Zero();
  for (int k = 0; k < n; ++k) {
    Eigen::Matrix<double, kStateCovSize, 1> z;
    for (int i = 0; i < kStateCovSize; ++i) z(i) = n01(rng);
    const Eigen::Matrix<double, kStateCovSize, 1> d = llt.matrixL() * z;
    const Eigen::Matrix3d R_s = R * lie::Exp(Eigen::Vector3d(d.segment<3>(kCovRot)));
    const Eigen::Vector3d theta_world = lie::Log(Eigen::Matrix3d(R_s * R.transpose()));
    const Eigen::Vector3d dv_imu =
        R_s.transpose() * (v_world + d.segment<3>(kCovVel)) - R.transpose() * v_world;
    S_rot += theta_world * theta_world.transpose();
    S_v += dv_imu * dv_imu.transpose();
  }
  S_rot /= n;
  S_v /= n;
  const Eigen::Matrix3d P_rot = P.block<3, 3>(kCovRot, kCovRot);
  EXPECT_LT((S_rot - P_rot).norm(), 0.02 * P_rot.norm());
  EXPECT_LT((S_v - P_v_imu).norm(), 0.02 * P_v_imu.norm());
}

}  // namespace
}  // namespace swlio::estimator

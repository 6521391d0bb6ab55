// The reported covariance's frames: the optimizer's body-frame rotation tangent becomes
// rotation about the world axes, and the velocity covariance in the IMU frame follows v_imu.

#include "swlio/estimator/window/state_covariance.h"

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

// Without a map tilt, the attitude against gravity is the world-axes rotation of P.
TEST(StateCovariance, GravityAttitudeWithoutTiltIsTheWorldRotationBlock) {
  Eigen::Matrix3d C_phi;
  C_phi << 4e-6, 1e-6, 0, 1e-6, 2e-6, 0, 0, 0, 9e-6;
  const Eigen::Matrix3d R = Yaw(0.9);
  const Eigen::Matrix3d P =
      GravityAttitudeCovariance(Eigen::Matrix2d::Zero(), Eigen::Matrix<double, 2, 3>::Zero(), C_phi,
                                Eigen::Vector2d::Zero(), R);
  EXPECT_TRUE(P.isApprox(R * C_phi * R.transpose(), 1e-12));
}

// Monte Carlo: sample the tilt and the frame's rotation error jointly (correlated, as the
// window leaves them), apply them as the optimizer does (θ additive, R ← R Exp(δφ)), and
// compare the sample covariance of the rotation error of Q·R with the first-order formula.
TEST(StateCovariance, GravityAttitudeMatchesSampledErrors) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  Eigen::Matrix<double, 5, 5> A;
  for (int i = 0; i < A.size(); ++i) A.data()[i] = n01(rng);
  const Eigen::Matrix<double, 5, 5> S = 1e-5 * (A * A.transpose() / 5.0);
  const Eigen::Vector2d tilt(0.004, -0.006);
  const Eigen::Matrix3d R =
      Yaw(-1.1) * Eigen::AngleAxisd(0.1, Eigen::Vector3d(0, 1, 1).normalized()).matrix();
  const Eigen::Matrix3d P = GravityAttitudeCovariance(
      S.topLeftCorner<2, 2>(), S.topRightCorner<2, 3>(), S.bottomRightCorner<3, 3>(), tilt, R);
  // The tilt's part alone is not negligible against the frame's (else the test could not tell).
  const double tilt_var = S.topLeftCorner<2, 2>().trace();
  const double phi_var = S.bottomRightCorner<3, 3>().trace();
  EXPECT_GT(tilt_var, 0.2 * phi_var);

  const Eigen::LLT<Eigen::Matrix<double, 5, 5>> llt(S);
  const Eigen::Matrix3d R_g = lie::Exp(Eigen::Vector3d(tilt.x(), tilt.y(), 0.0)) * R;
  const int n = 200000;
  Eigen::Matrix3d S_rot = Eigen::Matrix3d::Zero();
  for (int k = 0; k < n; ++k) {
    Eigen::Matrix<double, 5, 1> z;
    for (int i = 0; i < 5; ++i) z(i) = n01(rng);
    const Eigen::Matrix<double, 5, 1> d = llt.matrixL() * z;
    const Eigen::Vector3d tilt_s(tilt.x() + d(0), tilt.y() + d(1), 0.0);
    const Eigen::Matrix3d R_g_s = lie::Exp(tilt_s) * R * lie::Exp(Eigen::Vector3d(d.tail<3>()));
    const Eigen::Vector3d e = lie::Log(Eigen::Matrix3d(R_g_s * R_g.transpose()));
    S_rot += e * e.transpose();
  }
  S_rot /= n;
  EXPECT_LT((S_rot - P).norm(), 0.02 * P.norm());
  // Leaving the cross covariance out is measurably wrong: the test sees the correlation.
  const Eigen::Matrix3d P_uncorrelated =
      GravityAttitudeCovariance(S.topLeftCorner<2, 2>(), Eigen::Matrix<double, 2, 3>::Zero(),
                                S.bottomRightCorner<3, 3>(), tilt, R);
  EXPECT_GT((S_rot - P_uncorrelated).norm(), 0.05 * P.norm());
}

}  // namespace
}  // namespace swlio::estimator

#include "swlio/core/lie.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

namespace swlio::lie {
namespace {

constexpr double kPi = std::numbers::pi;

/// Central-difference Jacobian of f: R³ → R³ at 0.
Mat3 NumericJacobian(const std::function<Vec3(const Vec3&)>& f, double h = 1e-6) {
  Mat3 J;
  for (int i = 0; i < 3; ++i) {
    Vec3 d = Vec3::Zero();
    d(i) = h;
    J.col(i) = (f(d) - f(-d)) / (2.0 * h);
  }
  return J;
}

/// Rotation vectors covering zero, tiny, ordinary, large and near-π angles.
std::vector<Vec3> TestVectors() {
  std::vector<Vec3> v = {Vec3::Zero(),
                         Vec3(1e-9, -2e-9, 3e-9),
                         Vec3(1e-5, 2e-5, -1e-5),
                         Vec3(3e-3, -4e-3, 1e-3),  // just below the Taylor switch
                         Vec3(0.3, -0.2, 0.5),
                         Vec3(1.0, 2.0, -0.5),
                         Vec3(0.0, 0.0, kPi - 1e-3),
                         Vec3(1.0, 1.0, 1.0).normalized() * (kPi - 1e-4)};
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> angle(0.0, kPi - 1e-2);
  for (int i = 0; i < 20; ++i) {
    Vec3 axis(u(rng), u(rng), u(rng));
    v.push_back(axis.normalized() * angle(rng));
  }
  return v;
}

TEST(Lie, HatVeeAndCrossProduct) {
  const Vec3 a(1.0, -2.0, 3.0);
  const Vec3 b(0.5, 4.0, -1.0);
  EXPECT_TRUE((Hat(a) * b).isApprox(a.cross(b)));
  EXPECT_TRUE(Vee(Hat(a)).isApprox(a));
  EXPECT_TRUE((Hat(a) + Hat(a).transpose()).isZero());
}

TEST(Lie, ExpMatchesAngleAxisAndIsOrthonormal) {
  for (const Vec3& phi : TestVectors()) {
    const Mat3 R = Exp(phi);
    const double theta = phi.norm();
    const Mat3 expected =
        theta > 0.0 ? Eigen::AngleAxisd(theta, phi / theta).toRotationMatrix() : Mat3::Identity();
    EXPECT_TRUE(R.isApprox(expected, 1e-12)) << phi.transpose();
    EXPECT_TRUE((R * R.transpose()).isApprox(Mat3::Identity(), 1e-12));
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  }
}

TEST(Lie, LogInvertsExp) {
  for (const Vec3& phi : TestVectors()) {
    EXPECT_LT((Log(Exp(phi)) - phi).norm(), 1e-9 * std::max(1.0, phi.norm())) << phi.transpose();
    EXPECT_LT((QuatLog(QuatExp(phi)) - phi).norm(), 1e-12 + 1e-12 * phi.norm());
  }
}

TEST(Lie, AngleIsTheNormOfTheRotationVector) {
  for (const Vec3& phi : TestVectors()) {
    EXPECT_NEAR(Angle(Exp(phi)), phi.norm(), 1e-9) << phi.transpose();
  }
  // Beyond a half turn the same rotation is the shorter one the other way.
  EXPECT_NEAR(Angle(Exp(Vec3(0.0, 0.0, 1.5 * kPi))), 0.5 * kPi, 1e-9);
  EXPECT_NEAR(Angle(Eigen::Vector3d(1, -1, -1).asDiagonal()), kPi, 1e-9);
}

TEST(Lie, SmallAngleSeriesIsContinuousAcrossTheSwitch) {
  const Vec3 axis = Vec3(0.2, -0.7, 0.4).normalized();
  const Vec3 below = axis * (kTaylorAngle * (1.0 - 1e-9));
  const Vec3 above = axis * (kTaylorAngle * (1.0 + 1e-9));
  EXPECT_LT((RightJacobian(below) - RightJacobian(above)).norm(), 1e-10);
  EXPECT_LT((RightJacobianInverse(below) - RightJacobianInverse(above)).norm(), 1e-10);
  EXPECT_LT((QuatExp(below).coeffs() - QuatExp(above).coeffs()).norm(), 1e-10);
}

TEST(Lie, LogAtExactlyPiGivesAValidHalfTurn) {
  const std::vector<Mat3> half_turns = {
      Eigen::Vector3d(1, -1, -1).asDiagonal(), Eigen::Vector3d(-1, 1, -1).asDiagonal(),
      Eigen::Vector3d(-1, -1, 1).asDiagonal(), Exp(Vec3(1.0, 2.0, 2.0) / 3.0 * kPi)};
  for (const Mat3& R : half_turns) {
    const Vec3 phi = Log(R);
    EXPECT_NEAR(phi.norm(), kPi, 1e-9);
    EXPECT_TRUE(Exp(phi).isApprox(R, 1e-9));
  }
}

TEST(Lie, RightJacobianMatchesCentralDifferences) {
  for (const Vec3& phi : TestVectors()) {
    // Exp(phi + δ) = Exp(phi) Exp(Jr δ)  ⇒  Jr = ∂/∂δ Log(Exp(phi)ᵀ Exp(phi + δ)).
    const Mat3 R0t = Exp(phi).transpose();
    const Mat3 numeric = NumericJacobian([&](const Vec3& d) { return Log(R0t * Exp(phi + d)); });
    EXPECT_LT((numeric - RightJacobian(phi)).norm(), 1e-7) << phi.transpose();
  }
}

TEST(Lie, RightJacobianInverseMatchesCentralDifferences) {
  for (const Vec3& phi : TestVectors()) {
    // Log(Exp(phi) Exp(δ)) = phi + JrInv δ.
    const Mat3 R0 = Exp(phi);
    const Mat3 numeric = NumericJacobian([&](const Vec3& d) { return Log(R0 * Exp(d)); });
    EXPECT_LT((numeric - RightJacobianInverse(phi)).norm(), 1e-6) << phi.transpose();
    EXPECT_TRUE((RightJacobian(phi) * RightJacobianInverse(phi)).isApprox(Mat3::Identity(), 1e-9));
  }
}

TEST(Lie, LeftJacobiansMatchCentralDifferences) {
  for (const Vec3& phi : TestVectors()) {
    const Mat3 R0 = Exp(phi);
    const Mat3 jl =
        NumericJacobian([&](const Vec3& d) { return Log(Exp(phi + d) * R0.transpose()); });
    EXPECT_LT((jl - LeftJacobian(phi)).norm(), 1e-7) << phi.transpose();
    const Mat3 jl_inv = NumericJacobian([&](const Vec3& d) { return Log(Exp(d) * R0); });
    EXPECT_LT((jl_inv - LeftJacobianInverse(phi)).norm(), 1e-6) << phi.transpose();
  }
}

TEST(Lie, ExpDerivativeAtZeroIsHat) {
  const Vec3 phi(0.3, -0.1, 0.7);
  const double h = 1e-6;
  const Mat3 numeric = (Exp(h * phi) - Exp(-h * phi)) / (2.0 * h);
  EXPECT_LT((numeric - Hat(phi)).norm(), 1e-9);
}

TEST(Lie, SE3ExpLogRoundTripAndAdjoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    Vec6 xi;
    for (int k = 0; k < 6; ++k) xi(k) = 3.0 * u(rng);
    xi.tail<3>() = xi.tail<3>().normalized() * (std::abs(u(rng)) * (kPi - 1e-3));
    const Eigen::Isometry3d T = ExpSE3(xi);
    EXPECT_LT((LogSE3(T) - xi).norm(), 1e-9);

    Vec6 eta;
    for (int k = 0; k < 6; ++k) eta(k) = 0.2 * u(rng);
    const Eigen::Isometry3d lhs = T * ExpSE3(eta) * T.inverse();
    const Eigen::Isometry3d rhs = ExpSE3(Adjoint(T) * eta);
    EXPECT_TRUE(lhs.matrix().isApprox(rhs.matrix(), 1e-9));
  }
  EXPECT_TRUE(ExpSE3(Vec6::Zero()).matrix().isIdentity());
}

TEST(Lie, SE3ExpOfPureTranslation) {
  Vec6 xi = Vec6::Zero();
  xi.head<3>() = Vec3(1.0, 2.0, 3.0);
  EXPECT_TRUE(ExpSE3(xi).translation().isApprox(Vec3(1.0, 2.0, 3.0)));
}

TEST(Lie, QuaternionProductMatrices) {
  const Eigen::Quaterniond q = QuatExp(Vec3(0.1, 0.5, -0.3));
  const Eigen::Quaterniond p = QuatExp(Vec3(-0.7, 0.2, 0.4));
  const Eigen::Quaterniond qp = q * p;
  const Eigen::Vector4d qp_wxyz(qp.w(), qp.x(), qp.y(), qp.z());
  const Eigen::Vector4d q_wxyz(q.w(), q.x(), q.y(), q.z());
  const Eigen::Vector4d p_wxyz(p.w(), p.x(), p.y(), p.z());
  EXPECT_TRUE((QuatLeftMatrix(q) * p_wxyz).isApprox(qp_wxyz));
  EXPECT_TRUE((QuatRightMatrix(p) * q_wxyz).isApprox(qp_wxyz));
}

TEST(Lie, PositiveWAndRpyRoundTrip) {
  Eigen::Quaterniond q(-0.5, 0.5, 0.5, 0.5);
  EXPECT_GE(PositiveW(q).w(), 0.0);
  EXPECT_TRUE(PositiveW(q).toRotationMatrix().isApprox(q.toRotationMatrix()));
  const Vec3 rpy(0.3, -0.4, 2.5);
  const Eigen::Quaterniond r = QuatFromRpy(rpy.x(), rpy.y(), rpy.z());
  EXPECT_TRUE(RpyFromRotation(r.toRotationMatrix()).isApprox(rpy, 1e-12));
  // Yaw alone rotates x towards y.
  EXPECT_TRUE((QuatFromRpy(0, 0, kPi / 2) * Vec3::UnitX()).isApprox(Vec3::UnitY()));
}

}  // namespace
}  // namespace swlio::lie

// The window optimization's building blocks: the pose manifold's Plus/Minus against lie.h, and
// every factor's analytic Jacobians against central differences, ambient and tangent.

#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "jacobian_check.h"
#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/imu/imu_residual.h"
#include "swlio/estimator/registration/point_to_line_factor.h"
#include "swlio/estimator/registration/point_to_plane_factor.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Vector = ceres::Vector;
using Block = std::vector<double>;

constexpr double kG = 9.80665;

Block PoseBlock(const Vec3& p, const Vec3& rotation_vector) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::Exp(rotation_vector);
  T.translation() = p;
  Block x(kPoseSize);
  PoseToParameters(T, x.data());
  return x;
}

void Report(const std::string& name, const test::JacobianErrors& e) {
  for (size_t k = 0; k < e.ambient.size(); ++k) {
    std::printf("[ jacobian ] %s block %zu: ambient %.2e, tangent %.2e (relative max error)\n",
                name.c_str(), k, e.ambient[k], e.tangent[k]);
  }
}

// Ceres' manifold matchers (numeric differences of Plus and Minus). Their PlusMinusIsIdentityAt
// compares coefficients, and x ⊞ (y ⊟ x) may return −q_y (the same rotation: Minus takes the
// shortest rotation, so a window whose quaternions flip sign still gets small residuals); that
// invariant is checked as rotations below instead.
TEST(PoseManifold, SatisfiesCeresManifoldInvariants) {
  using ceres::HasCorrectMinusJacobianAt, ceres::HasCorrectPlusJacobianAt,
      ceres::HasCorrectRightMultiplyByPlusJacobianAt, ceres::MinusPlusIsIdentityAt,
      ceres::MinusPlusJacobianIsIdentityAt, ceres::XMinusXIsZeroAt, ceres::XPlusZeroIsXAt;
  const PoseManifold manifold;
  const Block xs[] = {PoseBlock({1.0, -2.0, 0.5}, {0.3, -0.2, 0.9}),
                      PoseBlock({0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}),
                      PoseBlock({-4.0, 3.0, 2.0}, {2.5, 0.4, -1.0})};
  const Block y = PoseBlock({2.0, 1.0, -1.0}, {-1.2, 0.6, 0.3});
  for (const Block& xb : xs) {
    const Vector x = Eigen::Map<const Vector>(xb.data(), kPoseSize);
    Vector delta(kPoseTangentSize);
    delta << 0.1, -0.3, 0.2, 0.4, -0.7, 1.1;
    const double tol = 1e-9;
    EXPECT_THAT(manifold, XPlusZeroIsXAt(x, tol));
    EXPECT_THAT(manifold, XMinusXIsZeroAt(x, tol));
    EXPECT_THAT(manifold, MinusPlusIsIdentityAt(x, delta, tol));
    const Vector zero = Vector::Zero(kPoseTangentSize);
    EXPECT_THAT(manifold, MinusPlusIsIdentityAt(x, zero, tol));
    EXPECT_THAT(manifold, HasCorrectPlusJacobianAt(x, tol));
    EXPECT_THAT(manifold, HasCorrectMinusJacobianAt(x, tol));
    EXPECT_THAT(manifold, MinusPlusJacobianIsIdentityAt(x, tol));
    EXPECT_THAT(manifold, HasCorrectRightMultiplyByPlusJacobianAt(x, tol));
    // x ⊞ (y ⊟ x) = y as a pose.
    double d[kPoseTangentSize];
    Block back(kPoseSize);
    ASSERT_TRUE(manifold.Minus(y.data(), xb.data(), d));
    ASSERT_TRUE(manifold.Plus(xb.data(), d, back.data()));
    const Eigen::Isometry3d Ty = PoseFromParameters(y.data());
    const Eigen::Isometry3d Tb = PoseFromParameters(back.data());
    EXPECT_LT((Ty.matrix() - Tb.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(PoseManifold, PlusIsRightRotationAndAdditivePosition) {
  const PoseManifold manifold;
  const Block x = PoseBlock({1.0, 2.0, 3.0}, {0.4, -0.5, 0.6});
  const double delta[6] = {0.3, -0.1, 0.2, -0.8, 0.5, 1.3};
  Block y(kPoseSize);
  ASSERT_TRUE(manifold.Plus(x.data(), delta, y.data()));
  const Eigen::Isometry3d Tx = PoseFromParameters(x.data());
  const Eigen::Isometry3d Ty = PoseFromParameters(y.data());
  const Vec3 dphi(delta[3], delta[4], delta[5]);
  EXPECT_LT((Ty.linear() - Tx.linear() * lie::Exp(dphi)).norm(), 1e-14);
  EXPECT_LT((Ty.translation() - Tx.translation() - Vec3(delta[0], delta[1], delta[2])).norm(),
            1e-14);
  // Round trip through Minus, for rotations up to 3 rad.
  for (double angle : {1e-9, 1e-4, 0.5, 2.0, 3.0}) {
    double d[6] = {0.5, -1.5, 2.0, 0.0, 0.0, 0.0};
    const Vec3 axis = Vec3(0.3, -0.9, 0.2).normalized() * angle;
    d[3] = axis.x(), d[4] = axis.y(), d[5] = axis.z();
    Block z(kPoseSize);
    ASSERT_TRUE(manifold.Plus(x.data(), d, z.data()));
    double back[6];
    ASSERT_TRUE(manifold.Minus(z.data(), x.data(), back));
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(back[i], d[i], 1e-12) << "angle " << angle;
  }
  // M Q = I at a unit quaternion.
  const PoseMinusJacobian M = PoseMinusJacobianAt(x.data());
  const PosePlusJacobian Q = PosePlusJacobianAt(x.data());
  EXPECT_LT((M * Q - Eigen::Matrix<double, 6, 6>::Identity()).norm(), 1e-14);
}

class ImuFactorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setup_ = sim::MakeSimSetup("aggressive", 3, 14.0);
    imu_ = test::ToImuSamples(sim::SimulateImu(*setup_->trajectory, setup_->imu, 3));
    Preintegrator pre(noise_, bg0_, ba0_);
    ASSERT_EQ(pre.Integrate(imu_, t_i_, t_j_), PreintegrationStatus::kOk);
    pim_ = pre.result();
  }
  // A frame's two blocks from a state.
  static void ToBlocks(const State& s, Block* pose, Block* speed_bias) {
    pose->resize(kPoseSize);
    PoseToParameters(s.T_world_imu, pose->data());
    speed_bias->resize(kSpeedBiasSize);
    Eigen::Map<Eigen::Matrix<double, 9, 1>> sb(speed_bias->data());
    sb << s.vel_world, s.bias_acc, s.bias_gyro;
  }

  std::optional<sim::SimSetup> setup_;
  std::vector<ImuSample> imu_;
  ImuNoiseConfig noise_;
  PreintegratedImu pim_;
  const int64_t t_i_ = SecToNs(6.0037);
  const int64_t t_j_ = SecToNs(6.1041);
  const Vec3 bg0_{0.003, -0.002, 0.001};
  const Vec3 ba0_{0.04, 0.01, -0.03};
};

TEST_F(ImuFactorTest, WhitensByThePreintegratedAndBiasWalkCovariance) {
  const std::unique_ptr<ImuFactor> f = ImuFactor::Create(pim_, noise_, kG);
  ASSERT_NE(f, nullptr);
  Mat15 cov = Mat15::Zero();
  cov.topLeftCorner<9, 9>() = pim_.covariance;
  cov.bottomRightCorner<6, 6>() = BiasWalkCovariance(noise_, pim_.dt_s);
  const Mat15& W = f->sqrt_information();
  EXPECT_LT((W.transpose() * W * cov - Mat15::Identity()).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_EQ(ImuFactor::Create(PreintegratedImu{}, noise_, kG), nullptr);  // Σ = 0

  // At the predicted state with frame i's biases carried over, the residual vanishes; a bias
  // step between the frames shows up, whitened, in the random-walk rows only.
  State si = test::TrueState(*setup_->trajectory, t_i_);
  si.bias_gyro = bg0_ + Vec3(1e-3, 0.0, -1e-3);
  si.bias_acc = ba0_ + Vec3(0.0, 0.01, 0.0);
  State sj = PredictState(si, pim_, GravityWorld(kG));
  Block pi, sbi, pj, sbj;
  ToBlocks(si, &pi, &sbi);
  ToBlocks(sj, &pj, &sbj);
  std::vector<Block> x = {pi, sbi, pj, sbj};
  EXPECT_LT(test::EvaluateResidual(*f, x).norm(), 1e-6);
  x[3][kSbBiasGyro + 1] += 2e-5;
  Eigen::Matrix<double, 15, 1> expected = Eigen::Matrix<double, 15, 1>::Zero();
  expected(kRowBiasGyro + 1) = 2e-5;
  expected = W * expected;
  EXPECT_LT((test::EvaluateResidual(*f, x) - expected).norm(), 1e-6 * expected.norm());
}

TEST_F(ImuFactorTest, JacobiansMatchCentralDifferences) {
  const std::unique_ptr<ImuFactor> f = ImuFactor::Create(pim_, noise_, kG);
  ASSERT_NE(f, nullptr);
  // States near (not at) the truth and biases away from the linearization point, so that every
  // term of the residual is exercised.
  State si = test::TrueState(*setup_->trajectory, t_i_);
  State sj = test::TrueState(*setup_->trajectory, t_j_);
  si.T_world_imu.linear() = si.T_world_imu.linear() * lie::Exp(Vec3(0.02, -0.03, 0.05));
  sj.T_world_imu.linear() = sj.T_world_imu.linear() * lie::Exp(Vec3(-0.04, 0.01, 0.03));
  si.vel_world += Vec3(0.1, -0.2, 0.05);
  sj.T_world_imu.translation() += Vec3(0.03, 0.01, -0.02);
  si.bias_gyro = bg0_ + Vec3(0.004, -0.003, 0.005);
  si.bias_acc = ba0_ + Vec3(0.02, 0.03, -0.01);
  sj.bias_gyro = si.bias_gyro + Vec3(1e-5, -2e-5, 3e-5);
  sj.bias_acc = si.bias_acc + Vec3(-1e-4, 2e-4, 1e-4);
  Block pi, sbi, pj, sbj;
  ToBlocks(si, &pi, &sbi);
  ToBlocks(sj, &pj, &sbj);
  const PoseManifold pose;
  const test::JacobianErrors e =
      test::CheckJacobians(*f, {pi, sbi, pj, sbj}, {&pose, nullptr, &pose, nullptr});
  Report("ImuFactor", e);
  // Whitened entries reach 1e6 (σ_p ≈ 1e-6 m over 0.1 s); relative to that scale:
  EXPECT_LT(e.Worst(), 1e-7);
}

struct LidarCase {
  Block pose, extrinsic;
  Vec3 point_lidar;
};

LidarCase MakeLidarCase() {
  LidarCase c;
  c.pose = PoseBlock({12.0, -4.0, 1.2}, {0.05, -0.1, 2.3});
  c.extrinsic = PoseBlock({0.1, 0.02, 0.3}, {0.01, -0.02, 1.5});
  c.point_lidar = Vec3(8.0, -3.0, 1.5);
  return c;
}

Vec3 WorldPoint(const LidarCase& c) {
  return PoseFromParameters(c.pose.data()) *
         (PoseFromParameters(c.extrinsic.data()) * c.point_lidar);
}

TEST(PointToPlaneFactor, ResidualIsTheSignedDistanceAndJacobiansMatch) {
  const LidarCase c = MakeLidarCase();
  const Vec3 n = Vec3(0.3, -0.5, 0.8).normalized();
  const Vec3 centroid = WorldPoint(c) + Vec3(0.2, 0.1, -0.3) + 4.0 * n.unitOrthogonal();
  const double s = 25.0;
  const auto f = PointToPlaneFactor::Create(c.point_lidar, 3.0 * n, centroid, s);
  ASSERT_NE(f, nullptr);
  std::vector<Block> x = {c.pose, c.extrinsic};
  EXPECT_NEAR(test::EvaluateResidual(*f, x)(0), s * n.dot(WorldPoint(c) - centroid), 1e-12);
  const PoseManifold pose;
  const test::JacobianErrors e = test::CheckJacobians(*f, x, {&pose, &pose});
  Report("PointToPlaneFactor", e);
  EXPECT_LT(e.Worst(), 1e-8);
  EXPECT_EQ(PointToPlaneFactor::Create(c.point_lidar, Vec3::Zero(), centroid), nullptr);
  EXPECT_EQ(PointToPlaneFactor::Create(c.point_lidar, n, centroid, 0.0), nullptr);
}

TEST(PointToLineFactor, ResidualNormIsTheDistanceAndJacobiansMatch) {
  const LidarCase c = MakeLidarCase();
  const double s = 10.0;
  for (const Vec3& d : {Vec3(0.0, 0.0, 1.0), Vec3(1.0, 0.0, 0.0), Vec3(0.4, -0.7, 0.2)}) {
    const Vec3 dn = d.normalized();
    const Vec3 centroid = WorldPoint(c) + Vec3(0.15, -0.1, 0.05) + 2.0 * dn;
    const auto f = PointToLineFactor::Create(c.point_lidar, -2.0 * d, centroid, s);
    ASSERT_NE(f, nullptr);
    std::vector<Block> x = {c.pose, c.extrinsic};
    const Vec3 u = WorldPoint(c) - centroid;
    const double distance = (u - dn * dn.dot(u)).norm();
    EXPECT_NEAR(test::EvaluateResidual(*f, x).norm(), s * distance, 1e-12);
    const PoseManifold pose;
    const test::JacobianErrors e = test::CheckJacobians(*f, x, {&pose, &pose});
    Report("PointToLineFactor", e);
    EXPECT_LT(e.Worst(), 1e-8);
  }
  EXPECT_EQ(PointToLineFactor::Create(c.point_lidar, Vec3::Zero(), Vec3::Zero()), nullptr);
}

}  // namespace
}  // namespace swlio::estimator

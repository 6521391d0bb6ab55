// GravityTiltImuFactor: the ImuFactor in a map frame tilted against gravity by an estimated
// rotation Q = Exp([θx, θy, 0]).

#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <optional>

#include "jacobian_check.h"
#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_residual.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Block = std::vector<double>;

constexpr double kG = 9.80665;

class GravityTiltImuFactorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setup_ = sim::MakeSimSetup("aggressive", 5, 14.0);
    const std::vector<ImuSample> imu =
        test::ToImuSamples(sim::SimulateImu(*setup_->trajectory, setup_->imu, 5));
    Preintegrator pre(noise_, bg0_, ba0_);
    ASSERT_EQ(pre.Integrate(imu, t_i_, t_j_), PreintegrationStatus::kOk);
    pim_ = pre.result();
    imu_ = ImuFactor::Create(pim_, noise_, kG);
    ASSERT_NE(imu_, nullptr);
  }
  static std::vector<Block> Blocks(const State& si, const State& sj, const Block& tilt) {
    std::vector<Block> x;
    for (const State* s : {&si, &sj}) {
      Block pose(kPoseSize), sb(kSpeedBiasSize);
      PoseToParameters(s->T_world_imu, pose.data());
      Eigen::Map<Eigen::Matrix<double, 9, 1>>(sb.data()) << s->vel_world, s->bias_acc, s->bias_gyro;
      x.push_back(pose);
      x.push_back(sb);
    }
    x.push_back(tilt);
    return x;
  }
  /// The state expressed in a frame rotated by R (world vectors → R · world vectors).
  static State InFrame(State s, const Eigen::Matrix3d& R) {
    s.T_world_imu = Eigen::Isometry3d(R) * s.T_world_imu;
    s.vel_world = R * s.vel_world;
    return s;
  }

  std::optional<sim::SimSetup> setup_;
  ImuNoiseConfig noise_;
  PreintegratedImu pim_;
  std::unique_ptr<ImuFactor> imu_;
  const int64_t t_i_ = SecToNs(7.0011);
  const int64_t t_j_ = SecToNs(7.1013);
  const Vec3 bg0_{0.002, -0.001, 0.0015};
  const Vec3 ba0_{0.03, -0.02, 0.01};
};

TEST_F(GravityTiltImuFactorTest, ZeroTiltIsThePlainImuFactor) {
  State si = test::TrueState(*setup_->trajectory, t_i_);
  State sj = test::TrueState(*setup_->trajectory, t_j_);
  sj.T_world_imu.translation() += Vec3(0.02, -0.01, 0.03);
  si.vel_world += Vec3(0.05, 0.0, -0.1);
  const GravityTiltImuFactor tilted(imu_.get());
  std::vector<Block> x = Blocks(si, sj, {0.0, 0.0});
  const Eigen::VectorXd r = test::EvaluateResidual(tilted, x);
  std::vector<Block> x4(x.begin(), x.begin() + 4);
  const Eigen::VectorXd r4 = test::EvaluateResidual(*imu_, x4);
  EXPECT_GT(r4.norm(), 1.0);  // the perturbation shows
  EXPECT_LT((r - r4).norm(), 1e-9 * r4.norm());
}

TEST_F(GravityTiltImuFactorTest, ExplainsStatesInATiltedMapFrame) {
  // States consistent with the IMU in the gravity-aligned frame, then written in a map frame
  // tilted by Q⁻¹ (map = Qᵀ · gravity frame): the plain factor sees gravity 0.3° off, the
  // tilted one at θ = θ_true sees nothing.
  const Vec3 theta_true(0.004, -0.003, 0.0);
  State si = test::TrueState(*setup_->trajectory, t_i_);
  si.bias_gyro = bg0_;
  si.bias_acc = ba0_;
  const State sj = PredictState(si, pim_, GravityWorld(kG));
  const Eigen::Matrix3d Qt = lie::Exp(theta_true).transpose();
  const State mi = InFrame(si, Qt), mj = InFrame(sj, Qt);
  const GravityTiltImuFactor tilted(imu_.get());
  std::vector<Block> at_truth = Blocks(mi, mj, {theta_true.x(), theta_true.y()});
  std::vector<Block> at_zero = Blocks(mi, mj, {0.0, 0.0});
  std::vector<Block> plain(at_zero.begin(), at_zero.begin() + 4);
  const double r_truth = test::EvaluateResidual(tilted, at_truth).norm();
  const double r_zero = test::EvaluateResidual(tilted, at_zero).norm();
  EXPECT_LT(r_truth, 1e-6);
  EXPECT_GT(r_zero, 1e3 * std::max(r_truth, 1e-9));
  EXPECT_NEAR(test::EvaluateResidual(*imu_, plain).norm(), r_zero, 1e-9 * r_zero);
  // The rotation itself: Q maps the map's vertical onto gravity's.
  EXPECT_LT(
      (GravityTiltRotation(at_truth[4].data()).toRotationMatrix() - lie::Exp(theta_true)).norm(),
      1e-12);
}

TEST_F(GravityTiltImuFactorTest, JacobiansMatchCentralDifferences) {
  State si = test::TrueState(*setup_->trajectory, t_i_);
  State sj = test::TrueState(*setup_->trajectory, t_j_);
  si.T_world_imu.linear() = si.T_world_imu.linear() * lie::Exp(Vec3(0.02, -0.03, 0.05));
  sj.T_world_imu.linear() = sj.T_world_imu.linear() * lie::Exp(Vec3(-0.04, 0.01, 0.03));
  si.T_world_imu.translation() += Vec3(12.0, -7.0, 0.5);  // far from the origin: Q moves p
  sj.T_world_imu.translation() += Vec3(12.03, -6.99, 0.48);
  si.vel_world += Vec3(0.1, -0.2, 0.05);
  si.bias_gyro = bg0_ + Vec3(0.004, -0.003, 0.005);
  si.bias_acc = ba0_ + Vec3(0.02, 0.03, -0.01);
  sj.bias_gyro = si.bias_gyro + Vec3(1e-5, -2e-5, 3e-5);
  sj.bias_acc = si.bias_acc + Vec3(-1e-4, 2e-4, 1e-4);
  const GravityTiltImuFactor tilted(imu_.get());
  const PoseManifold pose;
  const test::JacobianErrors e = test::CheckJacobians(tilted, Blocks(si, sj, {0.006, -0.004}),
                                                      {&pose, nullptr, &pose, nullptr, nullptr});
  for (size_t k = 0; k < e.ambient.size(); ++k) {
    std::printf("[ jacobian ] GravityTiltImuFactor block %zu: ambient %.2e, tangent %.2e\n", k,
                e.ambient[k], e.tangent[k]);
  }
  // As ImuFactor's check (whitened entries reach 1e6).
  EXPECT_LT(e.Worst(), 1e-6);
}

TEST_F(GravityTiltImuFactorTest, TiltColumnsAreAWorldRotationOfBothStates) {
  // At θ = 0, ∂r/∂θ_k is the plain factor's response to rotating both states about world axis
  // e_k: δp = e_k × p, δφ = Rᵀ e_k (right perturbation), δv = e_k × v; from ImuFactor's own
  // analytic Jacobians (an independent path to the central difference in the factor).
  State si = test::TrueState(*setup_->trajectory, t_i_);
  State sj = test::TrueState(*setup_->trajectory, t_j_);
  si.T_world_imu.translation() += Vec3(30.0, -20.0, 1.0);
  sj.T_world_imu.translation() += Vec3(30.02, -19.99, 0.97);
  std::vector<Block> x = Blocks(si, sj, {0.0, 0.0});
  const std::vector<test::RowMajorMatrix> J_tilted =
      test::AnalyticJacobians(GravityTiltImuFactor(imu_.get()), x);
  std::vector<Block> x4(x.begin(), x.begin() + 4);
  const std::vector<test::RowMajorMatrix> J = test::AnalyticJacobians(*imu_, x4);
  for (int k = 0; k < kGravityTiltSize; ++k) {
    const Vec3 axis = Vec3::Unit(k);
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(kImuFactorResiduals);
    for (int f = 0; f < 2; ++f) {
      const State& s = f == 0 ? si : sj;
      Eigen::Matrix<double, 6, 1> delta;
      delta << axis.cross(s.T_world_imu.translation()), s.T_world_imu.linear().transpose() * axis;
      const PosePlusJacobian plus = PosePlusJacobianAt(x[static_cast<size_t>(2 * f)].data());
      expected += J[static_cast<size_t>(2 * f)] * plus * delta;
      expected += J[static_cast<size_t>(2 * f + 1)].leftCols<3>() * axis.cross(s.vel_world);
    }
    const Eigen::VectorXd got = J_tilted[4].col(k);
    EXPECT_GT(expected.norm(), 1.0);
    EXPECT_LT((got - expected).norm(), 1e-5 * expected.norm()) << "axis " << k;
  }
}

}  // namespace
}  // namespace swlio::estimator

// Every analytic Jacobian of the pre-integration against central differences, and the
// first-order bias correction against re-integration.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_residual.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

constexpr double kG = 9.80665;

class PreintegrationJacobians : public ::testing::Test {
 protected:
  void SetUp() override {
    setup_ = sim::MakeSimSetup("aggressive", 3, 14.0);
    imu_ = test::ToImuSamples(sim::SimulateImu(*setup_->trajectory, setup_->imu, 3));
    t_i_ = SecToNs(6.0037);  // mid-step bounds
    t_j_ = SecToNs(7.0041);
  }
  Preintegrator Integrate(const Vec3& bg, const Vec3& ba) const {
    Preintegrator pre(ImuNoiseConfig{}, bg, ba);
    EXPECT_EQ(pre.Integrate(imu_, t_i_, t_j_), PreintegrationStatus::kOk);
    return pre;
  }

  std::optional<sim::SimSetup> setup_;
  std::vector<ImuSample> imu_;
  int64_t t_i_ = 0, t_j_ = 0;
  const Vec3 bg0_{0.003, -0.002, 0.001};
  const Vec3 ba0_{0.04, 0.01, -0.03};
};

// 9-vector difference of two integrations: [Log(ΔR_aᵀ ΔR_b); Δv_b − Δv_a; Δp_b − Δp_a].
Vec9 Minus(const PreintegratedImu& b, const PreintegratedImu& a) {
  Vec9 d;
  d << lie::Log(a.delta_R.transpose() * b.delta_R), b.delta_v - a.delta_v, b.delta_p - a.delta_p;
  return d;
}

TEST_F(PreintegrationJacobians, BiasJacobiansMatchCentralDifferences) {
  const PreintegratedImu nominal = Integrate(bg0_, ba0_).result();
  const double eps = 1e-6;
  Mat96 numeric;
  for (int c = 0; c < 6; ++c) {
    Vec3 dg = Vec3::Zero(), da = Vec3::Zero();
    (c < 3 ? dg : da)[c % 3] = eps;
    const PreintegratedImu plus = Integrate(bg0_ + dg, ba0_ + da).result();
    const PreintegratedImu minus = Integrate(bg0_ - dg, ba0_ - da).result();
    numeric.col(c) = (Minus(plus, nominal) - Minus(minus, nominal)) / (2.0 * eps);
  }
  const Mat96& analytic = nominal.jacobian_bias;
  EXPECT_LT((numeric - analytic).cwiseAbs().maxCoeff(), 1e-6 * analytic.cwiseAbs().maxCoeff())
      << "numeric\n"
      << numeric << "\nanalytic\n"
      << analytic;
  // The rotation does not depend on b_a.
  EXPECT_TRUE((analytic.block<3, 3>(kRowR, kColBa).isZero(0.0)));
  EXPECT_GT(nominal.J_v_bg().norm(), 1e-3);  // the test exercises a non-trivial coupling
}

TEST_F(PreintegrationJacobians, BiasCorrectionMatchesReintegration) {
  Preintegrator pre = Integrate(bg0_, ba0_);
  const Vec3 bg = bg0_ + Vec3(1e-3, -2e-3, 1.5e-3), ba = ba0_ + Vec3(0.03, -0.02, 0.05);
  const CorrectedDeltas corrected = Corrected(pre.result(), bg, ba);
  const PreintegratedImu exact = Integrate(bg, ba).result();
  const PreintegratedImu before = pre.result();
  const double rot = lie::Log(corrected.delta_R.transpose() * exact.delta_R).norm();
  const double vel = (corrected.delta_v - exact.delta_v).norm();
  const double pos = (corrected.delta_p - exact.delta_p).norm();
  // Zero-order error (no correction) for scale.
  const double rot0 = lie::Log(before.delta_R.transpose() * exact.delta_R).norm();
  const double vel0 = (before.delta_v - exact.delta_v).norm();
  const double pos0 = (before.delta_p - exact.delta_p).norm();
  EXPECT_LT(rot, 1e-3 * rot0);
  EXPECT_LT(vel, 1e-3 * vel0);
  EXPECT_LT(pos, 1e-3 * pos0);
  // Second order: |δθ| ≈ |δb_g| Δt = 2.7e-3 rad, so ½|δθ|²·|f|·Δt ≈ 4e-5 m/s.
  EXPECT_LT(rot, 1e-7);
  EXPECT_LT(vel, 1e-4);
  EXPECT_LT(pos, 5e-5);

  // Small change: first order; large change: UpdateBias re-integrates and matches exactly.
  EXPECT_FALSE(pre.NeedsReintegration(bg, ba));
  const Vec3 bg_far = bg0_ + Vec3(0.05, 0.0, 0.0);
  ASSERT_TRUE(pre.NeedsReintegration(bg_far, ba));
  const CorrectedDeltas updated = pre.UpdateBias(bg_far, ba);
  const PreintegratedImu far = Integrate(bg_far, ba).result();
  EXPECT_LT(lie::Log(updated.delta_R.transpose() * far.delta_R).norm(), 1e-12);
  EXPECT_LT((updated.delta_p - far.delta_p).norm(), 1e-12);
  EXPECT_TRUE(pre.result().bias_gyro_lin == bg_far);
  EXPECT_LT((pre.result().covariance - far.covariance).norm(), 1e-12 * far.covariance.norm());
}

// Residual Jacobians: perturb each of the 8 parameter blocks as documented in imu_residual.h.
TEST_F(PreintegrationJacobians, ResidualJacobiansMatchCentralDifferences) {
  const PreintegratedImu pim = Integrate(bg0_, ba0_).result();
  const Vec3 g = GravityWorld(kG);
  // States near (not at) the truth, and biases away from the linearization point, so that
  // every term (Jr⁻¹(r), Jr(J δb_g)) is exercised.
  NavPoint si = ToNavPoint(test::TrueState(*setup_->trajectory, t_i_));
  NavPoint sj = ToNavPoint(test::TrueState(*setup_->trajectory, t_j_));
  si.R_world_imu = si.R_world_imu * lie::Exp(Vec3(0.02, -0.03, 0.05));
  sj.R_world_imu = sj.R_world_imu * lie::Exp(Vec3(-0.04, 0.01, 0.03));
  si.v_world += Vec3(0.1, -0.2, 0.05);
  sj.p_world += Vec3(0.3, 0.1, -0.2);
  const Vec3 bg = bg0_ + Vec3(0.004, -0.003, 0.005), ba = ba0_ + Vec3(0.02, 0.03, -0.01);

  ImuResidualJacobians J;
  ImuResidual(pim, si, sj, bg, ba, g, &J);
  using Perturb = std::function<Vec9(const Vec3&)>;
  auto check = [&](const char* name, const Mat93& analytic, const Perturb& f) {
    const double eps = 1e-6;
    Mat93 numeric;
    for (int c = 0; c < 3; ++c) {
      const Vec3 d = Vec3::Unit(c) * eps;
      numeric.col(c) = (f(d) - f(-d)) / (2.0 * eps);
    }
    EXPECT_LT((numeric - analytic).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + analytic.norm()))
        << name << "\nnumeric\n"
        << numeric << "\nanalytic\n"
        << analytic;
  };
  auto res = [&](const NavPoint& a, const NavPoint& b, const Vec3& g_bias, const Vec3& a_bias) {
    return ImuResidual(pim, a, b, g_bias, a_bias, g);
  };
  check("R_i", J.R_i, [&](const Vec3& d) {
    NavPoint a = si;
    a.R_world_imu = a.R_world_imu * lie::Exp(d);
    return res(a, sj, bg, ba);
  });
  check("R_j", J.R_j, [&](const Vec3& d) {
    NavPoint b = sj;
    b.R_world_imu = b.R_world_imu * lie::Exp(d);
    return res(si, b, bg, ba);
  });
  check("p_i", J.p_i, [&](const Vec3& d) {
    NavPoint a = si;
    a.p_world += d;
    return res(a, sj, bg, ba);
  });
  check("p_j", J.p_j, [&](const Vec3& d) {
    NavPoint b = sj;
    b.p_world += d;
    return res(si, b, bg, ba);
  });
  check("v_i", J.v_i, [&](const Vec3& d) {
    NavPoint a = si;
    a.v_world += d;
    return res(a, sj, bg, ba);
  });
  check("v_j", J.v_j, [&](const Vec3& d) {
    NavPoint b = sj;
    b.v_world += d;
    return res(si, b, bg, ba);
  });
  check("bias_gyro", J.bias_gyro, [&](const Vec3& d) { return res(si, sj, bg + d, ba); });
  check("bias_acc", J.bias_acc, [&](const Vec3& d) { return res(si, sj, bg, ba + d); });
}

TEST_F(PreintegrationJacobians, ResidualVanishesAtThePredictedState) {
  const PreintegratedImu pim = Integrate(bg0_, ba0_).result();
  State start = test::TrueState(*setup_->trajectory, t_i_);
  start.bias_gyro = bg0_ + Vec3(1e-3, 0.0, -1e-3);
  start.bias_acc = ba0_ + Vec3(0.0, 0.01, 0.0);
  const State end = PredictState(start, pim, GravityWorld(kG));
  EXPECT_LT(ImuResidual(pim, start, end, GravityWorld(kG)).norm(), 1e-12);
}

}  // namespace
}  // namespace swlio::estimator

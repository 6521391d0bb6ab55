// Marginalization on a nonlinear window (IMU + LiDAR factors on simulated data): at the batch
// optimum the prior reproduces the batch's marginal and estimate, the prior's Jacobian is the
// first estimate, and a sliding window that marginalizes its oldest frame gives the batch solve.

#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <cstdio>

#include "ceres_test_util.h"
#include "jacobian_check.h"
#include "swlio/core/lie.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/window/marginalization.h"
#include "window_scenario.h"

namespace swlio::estimator {
namespace {

using Block = std::vector<double>;
using test::Borrowing;
using test::Hessian;
using test::LinearFactor;
using test::SchurKeepTail;
using test::Solve;

// ---------------------------------------------------------------------------------------------
// Nonlinear window: poses and speed/biases of simulated frames, IMU and LiDAR factors, a weak
// bias prior on frame 0 (as the static initialization provides), the extrinsic held constant.

struct Estimate {
  std::vector<Block> pose, speed_bias;
};

struct FrameError {
  double p_m = 0.0, R_rad = 0.0, v_mps = 0.0, ba_mps2 = 0.0, bg_radps = 0.0;
  void Max(const FrameError& o) {
    p_m = std::max(p_m, o.p_m), R_rad = std::max(R_rad, o.R_rad), v_mps = std::max(v_mps, o.v_mps);
    ba_mps2 = std::max(ba_mps2, o.ba_mps2), bg_radps = std::max(bg_radps, o.bg_radps);
  }
};

FrameError Difference(const Estimate& a, const Estimate& b, size_t k) {
  const Eigen::Isometry3d Ta = PoseFromParameters(a.pose[k].data());
  const Eigen::Isometry3d Tb = PoseFromParameters(b.pose[k].data());
  const Eigen::Map<const Eigen::Matrix<double, 9, 1>> sa(a.speed_bias[k].data());
  const Eigen::Map<const Eigen::Matrix<double, 9, 1>> sb(b.speed_bias[k].data());
  FrameError e;
  e.p_m = (Ta.translation() - Tb.translation()).norm();
  e.R_rad = lie::Log(Ta.linear().transpose() * Tb.linear()).norm();
  e.v_mps = (sa.segment<3>(kSbVel) - sb.segment<3>(kSbVel)).norm();
  e.ba_mps2 = (sa.segment<3>(kSbBiasAcc) - sb.segment<3>(kSbBiasAcc)).norm();
  e.bg_radps = (sa.segment<3>(kSbBiasGyro) - sb.segment<3>(kSbBiasGyro)).norm();
  return e;
}

class WindowMarginalization : public ::testing::Test {
 protected:
  void SetUp() override {
    s_ = test::MakeWindowScenario(kFrames, 11);
    for (const auto& f : s_.imu) ASSERT_NE(f, nullptr);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, kSpeedBiasSize);
    A.block<3, 3>(0, kSbBiasAcc) = Eigen::Matrix3d::Identity() / 0.1;    // σ_ba = 0.1 m/s²
    A.block<3, 3>(3, kSbBiasGyro) = Eigen::Matrix3d::Identity() / 0.01;  // σ_bg = 0.01 rad/s
    bias_prior_ =
        std::make_unique<LinearFactor>(std::vector<Eigen::MatrixXd>{A}, Eigen::VectorXd::Zero(6));
  }
  Estimate Initial() const { return {s_.pose_init, s_.speed_bias_init}; }

  // Frames first..last with the factors among them.
  void AddWindow(ceres::Problem* p, Estimate* e, size_t first, size_t last) {
    p->AddParameterBlock(s_.extrinsic.data(), kPoseSize, &manifold_);
    if (!estimate_extrinsic_) p->SetParameterBlockConstant(s_.extrinsic.data());
    for (size_t k = first; k <= last; ++k) {
      p->AddParameterBlock(e->pose[k].data(), kPoseSize, &manifold_);
      for (const auto& f : s_.lidar[k]) {
        p->AddResidualBlock(f.get(), nullptr, e->pose[k].data(), s_.extrinsic.data());
      }
      if (k == 0) p->AddResidualBlock(bias_prior_.get(), nullptr, e->speed_bias[0].data());
      if (k < last) {
        p->AddResidualBlock(s_.imu[k].get(), nullptr, e->pose[k].data(), e->speed_bias[k].data(),
                            e->pose[k + 1].data(), e->speed_bias[k + 1].data());
      }
    }
  }
  // Everything that touches frame k, marginalized onto frame k + 1.
  MarginalizationResult MarginalizeFrame(Estimate* e, size_t k, const MarginalizationResult* old) {
    Marginalizer m;
    m.AddParameterBlock(e->pose[k].data(), kPoseSize, &manifold_, BlockRole::kMarginalize);
    m.AddParameterBlock(e->speed_bias[k].data(), kSpeedBiasSize, nullptr, BlockRole::kMarginalize);
    m.AddParameterBlock(e->pose[k + 1].data(), kPoseSize, &manifold_, BlockRole::kKeep);
    m.AddParameterBlock(e->speed_bias[k + 1].data(), kSpeedBiasSize, nullptr, BlockRole::kKeep);
    m.AddParameterBlock(s_.extrinsic.data(), kPoseSize, &manifold_,
                        estimate_extrinsic_ ? BlockRole::kKeep : BlockRole::kConstant);
    for (const auto& f : s_.lidar[k]) {
      m.AddResidualBlock(f.get(), nullptr, {e->pose[k].data(), s_.extrinsic.data()});
    }
    if (k == 0) m.AddResidualBlock(bias_prior_.get(), nullptr, {e->speed_bias[0].data()});
    m.AddResidualBlock(s_.imu[k].get(), nullptr,
                       {e->pose[k].data(), e->speed_bias[k].data(), e->pose[k + 1].data(),
                        e->speed_bias[k + 1].data()});
    if (old != nullptr) m.AddResidualBlock(old->prior.get(), nullptr, old->kept_blocks);
    return m.Marginalize();
  }
  std::vector<double*> Blocks(Estimate* e, size_t first, size_t last) {
    std::vector<double*> b;
    for (size_t k = first; k <= last; ++k) {
      b.push_back(e->pose[k].data());
      b.push_back(e->speed_bias[k].data());
    }
    return b;
  }
  Estimate Batch() {
    Estimate e = Initial();
    ceres::Problem p(Borrowing());
    AddWindow(&p, &e, 0, kFrames - 1);
    const ceres::Solver::Summary summary = Solve(&p);
    EXPECT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
    return e;
  }
  // Windows of kWindow frames sliding by one; the oldest frame is marginalized (or, without
  // the prior, simply dropped) before the next frame comes in.
  Estimate Sliding(bool use_prior) {
    Estimate e = Initial();
    MarginalizationResult prior;
    for (size_t first = 0; first + kWindow <= kFrames; ++first) {
      const size_t last = first + kWindow - 1;
      ceres::Problem p(Borrowing());
      AddWindow(&p, &e, first, last);
      if (prior.prior != nullptr) p.AddResidualBlock(prior.prior.get(), nullptr, prior.kept_blocks);
      EXPECT_TRUE(Solve(&p).IsSolutionUsable());
      if (last + 1 == kFrames || !use_prior) continue;
      MarginalizationResult next = MarginalizeFrame(&e, first, first > 0 ? &prior : nullptr);
      EXPECT_EQ(next.status, MarginalizationStatus::kOk);
      EXPECT_EQ(next.rank, first == 0 ? kFirstPriorRank : kLaterPriorRank);
      prior = std::move(next);
    }
    return e;
  }

  static constexpr size_t kFrames = 5;
  static constexpr size_t kWindow = 3;
  // Frame 0's residuals carry 6 (LiDAR: pose) + 15 (IMU) + 6 (bias prior) = 27 dimensions of
  // information over frames 0 and 1; eliminating frame 0's 15 leaves 12 on frame 1 (one IMU
  // interval constrains v_0, v_1 and b_a only jointly). Later frames add the old prior's rows
  // (6 + 15 + 12 − 15 = 18 ≥ 15): full rank.
  static constexpr int kFirstPriorRank = 12;
  static constexpr int kLaterPriorRank = 15;
  test::WindowScenario s_;
  PoseManifold manifold_;
  std::unique_ptr<LinearFactor> bias_prior_;
  bool estimate_extrinsic_ = false;  ///< T_imu_lidar a variable (kept by the prior)
};

TEST_F(WindowMarginalization, AtTheBatchOptimumThePriorKeepsTheEstimateAndTheMarginal) {
  Estimate full = Batch();
  const Estimate optimum = full;
  ceres::Problem full_problem(Borrowing());
  AddWindow(&full_problem, &full, 0, kFrames - 1);
  const Eigen::MatrixXd H_full = Hessian(&full_problem, Blocks(&full, 0, kFrames - 1));

  const MarginalizationResult m = MarginalizeFrame(&full, 0, nullptr);
  ASSERT_EQ(m.status, MarginalizationStatus::kOk);
  EXPECT_EQ(m.marginalized_dim, 15);
  EXPECT_EQ(m.kept_dim, 15);
  EXPECT_EQ(m.rank, kFirstPriorRank);
  ceres::Problem reduced(Borrowing());
  AddWindow(&reduced, &full, 1, kFrames - 1);
  reduced.AddResidualBlock(m.prior.get(), nullptr, m.kept_blocks);
  // Same linearization point: the reduced Hessian is the Schur complement of the full one.
  const Eigen::MatrixXd H_star = SchurKeepTail(H_full, 15);
  const Eigen::MatrixXd H_reduced = Hessian(&reduced, Blocks(&full, 1, kFrames - 1));
  const double h_error = (H_reduced - H_star).norm() / H_star.norm();
  // Covariances in a common scale: C̃ = D C D with D = diag(H*)^½ (unit-diagonal information).
  const Eigen::VectorXd d = H_star.diagonal().cwiseSqrt();
  const Eigen::MatrixXd C_star = (d.asDiagonal() * H_star.inverse() * d.asDiagonal()).eval();
  const Eigen::MatrixXd C_reduced = (d.asDiagonal() * H_reduced.inverse() * d.asDiagonal()).eval();
  const double c_error = (C_reduced - C_star).cwiseAbs().maxCoeff() / C_star.cwiseAbs().maxCoeff();
  std::printf("[ marginal ] window at optimum: |H_prior - H*|/|H*| = %.2e, scaled cov error %.2e\n",
              h_error, c_error);
  EXPECT_LT(h_error, 1e-9);
  EXPECT_LT(c_error, 1e-6);

  // Started 3 cm / 0.3° away, the reduced problem returns to the batch optimum.
  for (size_t k = 1; k < kFrames; ++k) {
    full.pose[k][0] += 0.03;
    full.pose[k][4] += 0.003;
    full.speed_bias[k][1] += 0.05;
  }
  EXPECT_TRUE(Solve(&reduced).IsSolutionUsable());
  FrameError worst;
  for (size_t k = 1; k < kFrames; ++k) worst.Max(Difference(full, optimum, k));
  std::printf(
      "[ marginal ] window at optimum: re-solve differs by p %.1e m, R %.1e rad, v %.1e m/s\n",
      worst.p_m, worst.R_rad, worst.v_mps);
  EXPECT_LT(worst.p_m, 1e-9);
  EXPECT_LT(worst.R_rad, 1e-10);
  EXPECT_LT(worst.v_mps, 1e-8);
}

// With T_imu_lidar estimated online, frame 0's LiDAR factors also tie it in: the prior then
// spans [pose_1, speed_bias_1, T_imu_lidar], and the Schur-complement identity still holds.
TEST_F(WindowMarginalization, ExtrinsicEstimatedOnlineIsKeptByThePrior) {
  estimate_extrinsic_ = true;
  Estimate full = Batch();
  ceres::Problem full_problem(Borrowing());
  AddWindow(&full_problem, &full, 0, kFrames - 1);
  std::vector<double*> blocks = Blocks(&full, 0, kFrames - 1);
  blocks.push_back(s_.extrinsic.data());
  const Eigen::MatrixXd H_star = SchurKeepTail(Hessian(&full_problem, blocks), 15);

  const MarginalizationResult m = MarginalizeFrame(&full, 0, nullptr);
  ASSERT_EQ(m.status, MarginalizationStatus::kOk);
  ASSERT_EQ(m.kept_blocks, (std::vector<double*>{full.pose[1].data(), full.speed_bias[1].data(),
                                                 s_.extrinsic.data()}));
  EXPECT_EQ(m.kept_dim, 21);
  // Frame 0's points constrain only the product T_world_imu,0 · T_imu_lidar (6 dimensions), so
  // the count of kFirstPriorRank is unchanged; the information now spans all three blocks.
  EXPECT_EQ(m.rank, kFirstPriorRank);
  EXPECT_GT(m.prior->jacobian().rightCols(kPoseTangentSize).norm(), 0.0);
  ceres::Problem reduced(Borrowing());
  AddWindow(&reduced, &full, 1, kFrames - 1);
  reduced.AddResidualBlock(m.prior.get(), nullptr, m.kept_blocks);
  blocks.erase(blocks.begin(), blocks.begin() + 2);
  const Eigen::MatrixXd H_reduced = Hessian(&reduced, blocks);
  const double h_error = (H_reduced - H_star).norm() / H_star.norm();
  std::printf("[ marginal ] extrinsic kept: |H_prior - H*|/|H*| = %.2e\n", h_error);
  EXPECT_LT(h_error, 1e-12);
}

// The prior's Jacobian: at x₀ it is the derivative of r₀ + J₀ (x ⊟ x₀) (numeric check); away
// from x₀ it stays J₀ in the tangent (first estimate), while the residual follows x ⊟ x₀.
TEST_F(WindowMarginalization, PriorJacobianIsTheFirstEstimate) {
  Estimate e = Batch();
  const MarginalizationResult m = MarginalizeFrame(&e, 0, nullptr);
  ASSERT_EQ(m.status, MarginalizationStatus::kOk);
  const MarginalizationPrior& prior = *m.prior;
  std::vector<Block> x = {e.pose[1], e.speed_bias[1]};
  const test::JacobianErrors at_x0 = test::CheckJacobians(prior, x, {&manifold_, nullptr});
  std::printf("[ jacobian ] MarginalizationPrior at x0: pose %.2e / %.2e, speed_bias %.2e\n",
              at_x0.ambient[0], at_x0.tangent[0], at_x0.tangent[1]);
  EXPECT_LT(at_x0.Worst(), 1e-7);

  const double delta[kPoseTangentSize] = {0.05, -0.02, 0.03, 0.02, -0.01, 0.015};
  Block moved(kPoseSize);
  ASSERT_TRUE(manifold_.Plus(x[0].data(), delta, moved.data()));
  x[0] = moved;
  x[1][0] += 0.1;
  const std::vector<test::RowMajorMatrix> J = test::AnalyticJacobians(prior, x);
  test::RowMajorMatrix plus(kPoseSize, kPoseTangentSize);
  manifold_.PlusJacobian(x[0].data(), plus.data());
  const Eigen::MatrixXd& J0 = prior.jacobian();
  EXPECT_LT((J[0] * plus - J0.leftCols(kPoseTangentSize)).cwiseAbs().maxCoeff(),
            1e-12 * J0.cwiseAbs().maxCoeff());
  EXPECT_LT((J[1] - J0.rightCols(kSpeedBiasSize)).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(kPoseTangentSize + kSpeedBiasSize);
  dx.head<kPoseTangentSize>() = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(delta);
  dx(kPoseTangentSize) = 0.1;
  const Eigen::VectorXd expected = prior.residual() + J0 * dx;
  EXPECT_LT((test::EvaluateResidual(prior, x) - expected).norm(), 1e-9 * expected.norm());
}

TEST_F(WindowMarginalization, SlidingWindowWithPriorMatchesTheBatchSolve) {
  const Estimate batch = Batch();
  const Estimate with_prior = Sliding(true);
  const Estimate without_prior = Sliding(false);
  FrameError prior_error, drop_error, truth_error;
  for (size_t k = kFrames - kWindow; k < kFrames; ++k) {
    prior_error.Max(Difference(with_prior, batch, k));
    drop_error.Max(Difference(without_prior, batch, k));
    Estimate truth;
    truth.pose.assign(kFrames, Block(kPoseSize));
    truth.speed_bias.assign(kFrames, Block(kSpeedBiasSize, 0.0));
    PoseToParameters(s_.truth[k].T_world_imu, truth.pose[k].data());
    Eigen::Map<Eigen::Vector3d>{truth.speed_bias[k].data()} = s_.truth[k].vel_world;
    truth_error.Max(Difference(batch, truth, k));
  }
  auto print = [](const char* name, const FrameError& e) {
    std::printf("[ marginal ] %-26s p %.2e m, R %.2e rad, v %.2e m/s, ba %.2e, bg %.2e\n", name,
                e.p_m, e.R_rad, e.v_mps, e.ba_mps2, e.bg_radps);
  };
  print("sliding+prior vs batch:", prior_error);
  print("sliding, dropped vs batch:", drop_error);
  print("batch vs truth (pose, v):", truth_error);
  // The prior was linearized at estimates a few mm / 0.1° from the batch optimum; what it
  // loses is second order in that distance. Stated tolerances (measured ~1e-6, see report):
  EXPECT_LT(prior_error.p_m, 1e-5);
  EXPECT_LT(prior_error.R_rad, 1e-5);
  EXPECT_LT(prior_error.v_mps, 1e-4);
  EXPECT_LT(prior_error.ba_mps2, 1e-3);
  EXPECT_LT(prior_error.bg_radps, 1e-4);
  // Dropping the frame without the prior is far worse (what the prior is for).
  EXPECT_GT(drop_error.p_m, 100.0 * prior_error.p_m);
  EXPECT_GT(drop_error.v_mps, 100.0 * prior_error.v_mps);
  EXPECT_GT(drop_error.ba_mps2, 100.0 * prior_error.ba_mps2);
}

}  // namespace
}  // namespace swlio::estimator

// Marginalization: on a linear-Gaussian problem the prior reproduces the marginal of the full
// problem exactly; on a nonlinear window (IMU + LiDAR factors on simulated data) dropping the
// oldest frame through the prior gives the estimate of the full batch solve.

#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "ceres_test_util.h"
#include "jacobian_check.h"
#include "swlio/core/lie.h"
#include "swlio/estimator/imu_factor.h"
#include "swlio/estimator/marginalization.h"
#include "swlio/estimator/pose_manifold.h"
#include "window_scenario.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Block = std::vector<double>;
using test::Borrowing;
using test::Gradient;
using test::Hessian;
using test::LinearFactor;
using test::SchurKeepTail;
using test::Solve;

// ---------------------------------------------------------------------------------------------
// Linear-Gaussian problem: blocks a(2), b(3), c(2); factors on a, ab, bc, ac (robust), c.

class LinearMarginalization : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(7);
    std::normal_distribution<double> n01;
    auto random = [&](Eigen::Index r, Eigen::Index c) {
      Eigen::MatrixXd m(r, c);
      for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = n01(rng);
      return m;
    };
    auto factor = [&](std::vector<Eigen::Index> sizes, Eigen::Index rows) {
      std::vector<Eigen::MatrixXd> A;
      for (Eigen::Index s : sizes) A.push_back(random(rows, s));
      return std::make_unique<LinearFactor>(std::move(A), random(rows, 1));
    };
    f_a_ = factor({2}, 2);
    f_ab_ = factor({2, 3}, 3);
    f_bc_ = factor({3, 2}, 4);
    f_ac_ = factor({2, 2}, 2);
    f_c_ = factor({2}, 1);
    for (double& v : a_) v = n01(rng);
    for (double& v : b_) v = n01(rng);
    for (double& v : c_) v = n01(rng);
  }
  // All factors, or (with the prior) those that do not touch a.
  void Build(ceres::Problem* p, const MarginalizationResult* m) {
    if (m == nullptr) {
      p->AddResidualBlock(f_a_.get(), nullptr, a_);
      p->AddResidualBlock(f_ab_.get(), nullptr, a_, b_);
      p->AddResidualBlock(f_ac_.get(), loss_.get(), a_, c_);
    } else {
      p->AddResidualBlock(m->prior.get(), nullptr, m->kept_blocks);
    }
    p->AddResidualBlock(f_bc_.get(), nullptr, b_, c_);
    p->AddResidualBlock(f_c_.get(), nullptr, c_);
  }
  MarginalizationResult Marginalize(const ceres::LossFunction* loss) {
    Marginalizer m;
    m.AddParameterBlock(a_, 2, nullptr, BlockRole::kMarginalize);
    m.AddParameterBlock(b_, 3, nullptr, BlockRole::kKeep);
    m.AddParameterBlock(c_, 2, nullptr, BlockRole::kKeep);
    m.AddResidualBlock(f_a_.get(), nullptr, {a_});
    m.AddResidualBlock(f_ab_.get(), nullptr, {a_, b_});
    m.AddResidualBlock(f_ac_.get(), loss, {a_, c_});
    return m.Marginalize();
  }

  std::unique_ptr<LinearFactor> f_a_, f_ab_, f_bc_, f_ac_, f_c_;
  std::unique_ptr<ceres::LossFunction> loss_;
  double a_[2], b_[3], c_[2];
};

TEST_F(LinearMarginalization, PriorGivesTheMarginalOfTheFullProblem) {
  const MarginalizationResult m = Marginalize(nullptr);
  ASSERT_EQ(m.status, MarginalizationStatus::kOk);
  ASSERT_EQ(m.kept_blocks, (std::vector<double*>{b_, c_}));
  EXPECT_EQ(m.marginalized_dim, 2);
  EXPECT_EQ(m.kept_dim, 5);
  EXPECT_EQ(m.rank, 5);

  ceres::Problem full(Borrowing());
  Build(&full, nullptr);
  const Eigen::MatrixXd H_full = Hessian(&full, {a_, b_, c_});
  const Eigen::MatrixXd cov_full = H_full.inverse().bottomRightCorner(5, 5);
  ceres::Problem reduced(Borrowing());
  Build(&reduced, &m);
  const Eigen::MatrixXd cov_reduced = Hessian(&reduced, {b_, c_}).inverse();
  const double cov_error = (cov_full - cov_reduced).cwiseAbs().maxCoeff();
  std::printf("[ marginal ] linear: max |cov_full - cov_prior| = %.2e (max |cov| %.2e)\n",
              cov_error, cov_full.cwiseAbs().maxCoeff());
  EXPECT_LT(cov_error, 1e-9);

  // Means: the reduced solve gives the full solve's (b, c).
  Solve(&full);
  const Eigen::Matrix<double, 5, 1> x_full(b_[0], b_[1], b_[2], c_[0], c_[1]);
  for (double& v : b_) v += 3.0;  // start the reduced solve elsewhere
  Solve(&reduced);
  const Eigen::Matrix<double, 5, 1> x_reduced(b_[0], b_[1], b_[2], c_[0], c_[1]);
  std::printf("[ marginal ] linear: max |x_full - x_prior| = %.2e\n",
              (x_full - x_reduced).cwiseAbs().maxCoeff());
  EXPECT_LT((x_full - x_reduced).cwiseAbs().maxCoeff(), 1e-9);
}

TEST_F(LinearMarginalization, RobustLossIsFoldedInAsCeresDoes) {
  // The Schur complement of Ceres' own robustified Gauss–Newton system (H, g) must match the
  // prior's (J₀ᵀJ₀, J₀ᵀr₀) plus the factors that do not touch a. TolerantLoss has ρ'' > 0 (the
  // full Triggs correction, α ≠ 0); Cauchy (ρ'' < 0) and Huber (ρ'' = 0) are a √ρ' re-weighting.
  // The robust factor's squared residual is checked to lie in every loss's robust region.
  std::vector<std::unique_ptr<ceres::LossFunction>> losses;
  losses.push_back(std::make_unique<ceres::TolerantLoss>(0.5, 1.0));
  losses.push_back(std::make_unique<ceres::CauchyLoss>(0.5));
  losses.push_back(std::make_unique<ceres::HuberLoss>(0.3));
  ceres::Problem rest(Borrowing());
  rest.AddResidualBlock(f_bc_.get(), nullptr, b_, c_);
  rest.AddResidualBlock(f_c_.get(), nullptr, c_);
  const Eigen::MatrixXd H_rest = Hessian(&rest, {b_, c_});
  const Eigen::VectorXd g_rest = Gradient(&rest, {b_, c_});
  double r_ac[2];
  const double* x_ac[] = {a_, c_};
  ASSERT_TRUE(f_ac_->Evaluate(x_ac, r_ac, nullptr));
  ASSERT_GT(r_ac[0] * r_ac[0] + r_ac[1] * r_ac[1], 0.25);
  for (std::unique_ptr<ceres::LossFunction>& loss : losses) {
    loss_ = std::move(loss);
    const MarginalizationResult m = Marginalize(loss_.get());
    ASSERT_EQ(m.status, MarginalizationStatus::kOk);
    ceres::Problem full(Borrowing());
    Build(&full, nullptr);
    const Eigen::MatrixXd H = Hessian(&full, {a_, b_, c_});
    const Eigen::VectorXd g = Gradient(&full, {a_, b_, c_});
    const Eigen::MatrixXd H_star = SchurKeepTail(H, 2);
    const Eigen::VectorXd g_star =
        g.tail(5) - H.bottomLeftCorner(5, 2) * H.topLeftCorner(2, 2).inverse() * g.head(2);
    const Eigen::MatrixXd& J0 = m.prior->jacobian();
    EXPECT_LT((J0.transpose() * J0 + H_rest - H_star).cwiseAbs().maxCoeff(), 1e-12 * H_star.norm());
    EXPECT_LT((J0.transpose() * m.prior->residual() + g_rest - g_star).norm(),
              1e-12 * g_star.norm());
  }
}

// A dropped block u seen by a single one-row factor (with b): the row fixes one direction of u
// and says nothing about b, so the prior must be the one without that factor (pseudo-inverse
// semantics for the rank-deficient J_m).
TEST_F(LinearMarginalization, FreeDroppedDirectionsAbsorbTheirResiduals) {
  double u[2] = {0.3, -0.2};
  Eigen::MatrixXd A_u(1, 2), A_b(1, 3);
  A_u << 0.7, -1.1;
  A_b << 0.4, 0.9, -0.3;
  const LinearFactor f_ub({A_u, A_b}, Eigen::VectorXd::Constant(1, 0.5));
  Marginalizer m;
  m.AddParameterBlock(a_, 2, nullptr, BlockRole::kMarginalize);
  m.AddParameterBlock(u, 2, nullptr, BlockRole::kMarginalize);
  m.AddParameterBlock(b_, 3, nullptr, BlockRole::kKeep);
  m.AddParameterBlock(c_, 2, nullptr, BlockRole::kKeep);
  m.AddResidualBlock(f_a_.get(), nullptr, {a_});
  m.AddResidualBlock(f_ab_.get(), nullptr, {a_, b_});
  m.AddResidualBlock(f_ac_.get(), nullptr, {a_, c_});
  m.AddResidualBlock(&f_ub, nullptr, {u, b_});
  const MarginalizationResult with_u = m.Marginalize();
  const MarginalizationResult without_u = Marginalize(nullptr);
  ASSERT_EQ(with_u.status, MarginalizationStatus::kOk);
  EXPECT_EQ(with_u.marginalized_dim, 4);
  EXPECT_EQ(with_u.rank, without_u.rank);
  const Eigen::MatrixXd& J1 = with_u.prior->jacobian();
  const Eigen::MatrixXd& J2 = without_u.prior->jacobian();
  const Eigen::MatrixXd H2 = J2.transpose() * J2;
  EXPECT_LT((J1.transpose() * J1 - H2).cwiseAbs().maxCoeff(), 1e-12 * H2.norm());
  const Eigen::VectorXd g2 = J2.transpose() * without_u.prior->residual();
  EXPECT_LT((J1.transpose() * with_u.prior->residual() - g2).norm(), 1e-12 * g2.norm());
}

TEST_F(LinearMarginalization, ReportsMisuse) {
  Marginalizer unknown;
  unknown.AddParameterBlock(a_, 2, nullptr, BlockRole::kMarginalize);
  unknown.AddResidualBlock(f_ab_.get(), nullptr, {a_, b_});
  EXPECT_EQ(unknown.Marginalize().status, MarginalizationStatus::kUnknownBlock);
  Marginalizer nothing_kept;
  nothing_kept.AddParameterBlock(a_, 2, nullptr, BlockRole::kMarginalize);
  nothing_kept.AddResidualBlock(f_a_.get(), nullptr, {a_});
  EXPECT_EQ(nothing_kept.Marginalize().status, MarginalizationStatus::kNothingToKeep);
  Marginalizer wrong_size;
  wrong_size.AddParameterBlock(a_, 3, nullptr, BlockRole::kMarginalize);
  wrong_size.AddParameterBlock(b_, 3, nullptr, BlockRole::kKeep);
  wrong_size.AddResidualBlock(f_ab_.get(), nullptr, {a_, b_});
  EXPECT_EQ(wrong_size.Marginalize().status, MarginalizationStatus::kBadBlock);
}

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
    p->SetParameterBlockConstant(s_.extrinsic.data());
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
    m.AddParameterBlock(s_.extrinsic.data(), kPoseSize, &manifold_, BlockRole::kConstant);
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

// Marginalization on a linear-Gaussian problem: the prior reproduces the marginal of the full
// problem exactly, robust losses are folded in as Ceres does, and misuse is reported.

#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "ceres_test_util.h"
#include "swlio/estimator/window/marginalization.h"

namespace swlio::estimator {
namespace {

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

}  // namespace
}  // namespace swlio::estimator

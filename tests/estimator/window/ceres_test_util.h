#pragma once
/// @file
/// Test helpers around a Ceres problem: a linear-Gaussian factor, solving to tight tolerances,
/// and the dense Gauss–Newton Hessian of a problem in its tangent spaces.

#include <ceres/cost_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <utility>
#include <vector>

namespace swlio::test {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// r = Σ_k A_k x_k − z: a linear-Gaussian measurement over Euclidean blocks.
class LinearFactor final : public ceres::CostFunction {
 public:
  LinearFactor(std::vector<Eigen::MatrixXd> A, Eigen::VectorXd z)
      : A_(std::move(A)), z_(std::move(z)) {
    set_num_residuals(static_cast<int>(z_.size()));
    for (const Eigen::MatrixXd& a : A_) {
      mutable_parameter_block_sizes()->push_back(static_cast<int32_t>(a.cols()));
    }
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, z_.size());
    r = -z_;
    for (size_t k = 0; k < A_.size(); ++k) {
      r += A_[k] * Eigen::Map<const Eigen::VectorXd>(x[k], A_[k].cols());
      if (jacobians != nullptr && jacobians[k] != nullptr) {
        Eigen::Map<RowMajorMatrix>(jacobians[k], A_[k].rows(), A_[k].cols()) = A_[k];
      }
    }
    return true;
  }

 private:
  const std::vector<Eigen::MatrixXd> A_;
  const Eigen::VectorXd z_;
};

inline ceres::Problem::Options Borrowing() {
  ceres::Problem::Options o;
  o.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  o.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return o;
}

inline ceres::Solver::Summary Solve(ceres::Problem* problem) {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = 100;
  o.function_tolerance = 1e-16;
  o.gradient_tolerance = 1e-16;
  o.parameter_tolerance = 1e-14;
  o.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(o, problem, &summary);
  return summary;
}

// Gauss–Newton Hessian JᵀJ of a problem in the tangent spaces of `blocks` (in that order).
inline Eigen::MatrixXd Hessian(ceres::Problem* problem, const std::vector<double*>& blocks) {
  ceres::Problem::EvaluateOptions eo;
  eo.parameter_blocks = blocks;
  ceres::CRSMatrix crs;
  EXPECT_TRUE(problem->Evaluate(eo, nullptr, nullptr, nullptr, &crs));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int i = crs.rows[static_cast<size_t>(r)]; i < crs.rows[static_cast<size_t>(r) + 1]; ++i) {
      J(r, crs.cols[static_cast<size_t>(i)]) = crs.values[static_cast<size_t>(i)];
    }
  }
  return J.transpose() * J;
}

// Gradient of a problem in the tangent spaces of `blocks`.
inline Eigen::VectorXd Gradient(ceres::Problem* problem, const std::vector<double*>& blocks) {
  ceres::Problem::EvaluateOptions eo;
  eo.parameter_blocks = blocks;
  std::vector<double> g;
  EXPECT_TRUE(problem->Evaluate(eo, nullptr, nullptr, &g, nullptr));
  return Eigen::Map<const Eigen::VectorXd>(g.data(), static_cast<Eigen::Index>(g.size()));
}

inline Eigen::MatrixXd SchurKeepTail(const Eigen::MatrixXd& H, Eigen::Index drop) {
  const Eigen::Index n = H.rows() - drop;
  return H.bottomRightCorner(n, n) - H.bottomLeftCorner(n, drop) *
                                         H.topLeftCorner(drop, drop).inverse() *
                                         H.topRightCorner(drop, n);
}

}  // namespace swlio::test

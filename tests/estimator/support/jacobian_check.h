#pragma once
/// @file
/// Test helper: a cost function's analytic Jacobians against central differences, both in the
/// ambient coordinates (raw parameter values) and in the tangent of each block's manifold.

#include <ceres/cost_function.h>
#include <ceres/manifold.h>

#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace swlio::test {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Per parameter block: max |analytic − numeric| relative to max(1, max |analytic|).
struct JacobianErrors {
  std::vector<double> ambient;
  std::vector<double> tangent;
  double Worst() const {
    double w = 0.0;
    for (double e : ambient) w = std::max(w, e);
    for (double e : tangent) w = std::max(w, e);
    return w;
  }
};

inline Eigen::VectorXd EvaluateResidual(const ceres::CostFunction& f,
                                        std::vector<std::vector<double>>& x) {
  std::vector<const double*> ptrs;
  for (const std::vector<double>& b : x) ptrs.push_back(b.data());
  Eigen::VectorXd r(f.num_residuals());
  f.Evaluate(ptrs.data(), r.data(), nullptr);
  return r;
}

/// Analytic ambient Jacobians of every block (row-major, residuals × ambient size).
inline std::vector<RowMajorMatrix> AnalyticJacobians(const ceres::CostFunction& f,
                                                     std::vector<std::vector<double>>& x) {
  std::vector<RowMajorMatrix> J;
  std::vector<double*> jptrs;
  std::vector<const double*> ptrs;
  for (const std::vector<double>& b : x) {
    J.emplace_back(f.num_residuals(), static_cast<Eigen::Index>(b.size()));
    ptrs.push_back(b.data());
  }
  for (RowMajorMatrix& m : J) jptrs.push_back(m.data());
  Eigen::VectorXd r(f.num_residuals());
  f.Evaluate(ptrs.data(), r.data(), jptrs.data());
  return J;
}

/// `manifolds[k]` null for Euclidean blocks.
inline JacobianErrors CheckJacobians(const ceres::CostFunction& f,
                                     std::vector<std::vector<double>> x,
                                     const std::vector<const ceres::Manifold*>& manifolds,
                                     double eps = 1e-6) {
  JacobianErrors errors;
  const std::vector<RowMajorMatrix> J = AnalyticJacobians(f, x);
  for (size_t k = 0; k < x.size(); ++k) {
    const int a = static_cast<int>(x[k].size());
    const ceres::Manifold* m = manifolds[k];
    const int t = m != nullptr ? m->TangentSize() : a;
    const std::vector<double> x0 = x[k];
    const double scale = std::max(1.0, J[k].cwiseAbs().maxCoeff());
    // Ambient: raw coefficients.
    RowMajorMatrix numeric(f.num_residuals(), a);
    for (int c = 0; c < a; ++c) {
      x[k] = x0;
      x[k][static_cast<size_t>(c)] += eps;
      const Eigen::VectorXd plus = EvaluateResidual(f, x);
      x[k][static_cast<size_t>(c)] -= 2.0 * eps;
      numeric.col(c) = (plus - EvaluateResidual(f, x)) / (2.0 * eps);
    }
    errors.ambient.push_back((numeric - J[k]).cwiseAbs().maxCoeff() / scale);
    // Tangent: x ⊞ ±eps e_c against J · PlusJacobian.
    RowMajorMatrix plus_jacobian = RowMajorMatrix::Identity(a, t);
    if (m != nullptr) m->PlusJacobian(x0.data(), plus_jacobian.data());
    const RowMajorMatrix analytic_tangent = J[k] * plus_jacobian;
    RowMajorMatrix numeric_tangent(f.num_residuals(), t);
    for (int c = 0; c < t; ++c) {
      Eigen::VectorXd r[2];
      for (int s = 0; s < 2; ++s) {
        Eigen::VectorXd delta = Eigen::VectorXd::Zero(t);
        delta(c) = s == 0 ? eps : -eps;
        x[k] = x0;
        if (m != nullptr) {
          m->Plus(x0.data(), delta.data(), x[k].data());
        } else {
          for (int i = 0; i < a; ++i) x[k][static_cast<size_t>(i)] += delta(i);
        }
        r[s] = EvaluateResidual(f, x);
      }
      numeric_tangent.col(c) = (r[0] - r[1]) / (2.0 * eps);
    }
    errors.tangent.push_back((numeric_tangent - analytic_tangent).cwiseAbs().maxCoeff() / scale);
    x[k] = x0;
  }
  return errors;
}

}  // namespace swlio::test

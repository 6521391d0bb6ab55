#include "swlio/estimator/registration/lidar_rows.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <vector>

namespace swlio::estimator {

LidarRows CompressToRows(const Eigen::MatrixXd& H,
                         const Eigen::VectorXd& b,
                         const Eigen::MatrixXd& floor_covariance,
                         double min_eigenvalue) {
  LidarRows out;
  const Eigen::Index n = H.rows();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H);
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (es.eigenvalues()(i) >= min_eigenvalue && es.eigenvalues()(i) > 0.0) keep.push_back(i);
  }
  out.degenerate = static_cast<int>(n) - static_cast<int>(keep.size());
  if (keep.empty()) return out;
  const auto k = static_cast<Eigen::Index>(keep.size());
  Eigen::MatrixXd Vk(n, k);
  Eigen::VectorXd inv_lambda(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    Vk.col(j) = es.eigenvectors().col(keep[static_cast<size_t>(j)]);
    inv_lambda(j) = 1.0 / es.eigenvalues()(keep[static_cast<size_t>(j)]);
  }
  const Eigen::VectorXd delta_opt = -Vk * (inv_lambda.asDiagonal() * (Vk.transpose() * b));
  const Eigen::MatrixXd S =
      Eigen::MatrixXd(inv_lambda.asDiagonal()) + Vk.transpose() * floor_covariance * Vk;
  const Eigen::LLT<Eigen::MatrixXd> llt(S.inverse());
  if (llt.info() != Eigen::Success) {
    out.degenerate = static_cast<int>(n);
    return out;
  }
  out.U = Eigen::MatrixXd(llt.matrixL()).transpose() * Vk.transpose();
  out.r0 = -out.U * delta_opt;
  return out;
}

}  // namespace swlio::estimator

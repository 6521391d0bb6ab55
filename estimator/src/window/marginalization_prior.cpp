#include "swlio/estimator/window/marginalization_prior.h"

#include <utility>

namespace swlio::estimator {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace

MarginalizationPrior::MarginalizationPrior(std::vector<Block> blocks,
                                           Eigen::MatrixXd jacobian,
                                           Eigen::VectorXd residual)
    : blocks_(std::move(blocks)), jacobian_(std::move(jacobian)), residual_(std::move(residual)) {
  set_num_residuals(static_cast<int>(residual_.size()));
  for (const Block& b : blocks_) {
    mutable_parameter_block_sizes()->push_back(static_cast<int32_t>(b.x0.size()));
  }
}

bool MarginalizationPrior::Evaluate(double const* const* parameters,
                                    double* residuals,
                                    double** jacobians) const {
  const Eigen::Index rows = residual_.size();
  Eigen::Map<Eigen::VectorXd> r(residuals, rows);
  r = residual_;
  Eigen::VectorXd dx;
  for (size_t k = 0; k < blocks_.size(); ++k) {
    const Block& b = blocks_[k];
    const Eigen::Index ambient = b.x0.size();
    dx.resize(b.tangent_size);
    if (b.manifold != nullptr) {
      if (!b.manifold->Minus(parameters[k], b.x0.data(), dx.data())) return false;
    } else {
      dx = Eigen::Map<const Eigen::VectorXd>(parameters[k], ambient) - b.x0;
    }
    const auto J0 = jacobian_.middleCols(b.tangent_offset, b.tangent_size);
    r += J0 * dx;
    if (jacobians == nullptr || jacobians[k] == nullptr) continue;
    Eigen::Map<RowMajorMatrix> J(jacobians[k], rows, ambient);
    if (b.manifold == nullptr) {
      J = J0;
      continue;
    }
    RowMajorMatrix minus_jacobian(b.tangent_size, ambient);
    if (!b.manifold->MinusJacobian(parameters[k], minus_jacobian.data())) return false;
    J = J0 * minus_jacobian;
  }
  return true;
}

}  // namespace swlio::estimator

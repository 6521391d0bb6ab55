#include "swlio/estimator/window/marginalization.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <utility>

namespace swlio::estimator {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Folds a robust loss into (r, J) as Ceres does (the formulas in the header).
void ApplyLoss(const ceres::LossFunction& loss,
               Eigen::VectorXd* r,
               std::vector<Eigen::MatrixXd>* J) {
  const double s = r->squaredNorm();
  double rho[3];
  loss.Evaluate(s, rho);
  const double sqrt_rho1 = std::sqrt(std::max(rho[1], 0.0));
  double alpha = 0.0;
  if (s > 0.0 && rho[2] > 0.0 && rho[1] > 0.0)
    alpha = 1.0 - std::sqrt(1.0 + 2.0 * s * rho[2] / rho[1]);
  for (Eigen::MatrixXd& Jk : *J) {
    if (Jk.size() == 0) continue;
    if (alpha != 0.0) Jk -= (alpha / s) * (*r) * (r->transpose() * Jk);
    Jk *= sqrt_rho1;
  }
  *r *= sqrt_rho1 / (1.0 - alpha);
}

// Column scaling D = diag(1/‖column‖) (1 for empty columns): whitened factors put columns of
// norm ~1 and ~1e6 side by side, and the rank decision must not depend on units.
Eigen::VectorXd ColumnScaling(const Eigen::MatrixXd& J) {
  const Eigen::ArrayXd norms = J.colwise().norm().transpose().array();
  return (norms > 0.0).select(norms.inverse(), 1.0).matrix();
}

// Upper-trapezoidal R (rows × cols) of a QR, below-diagonal entries cleared.
Eigen::MatrixXd UpperRows(const Eigen::MatrixXd& qr_matrix, Eigen::Index rows) {
  Eigen::MatrixXd R = qr_matrix.topRows(rows);
  for (Eigen::Index i = 0; i < R.rows(); ++i) {
    for (Eigen::Index j = 0; j < std::min(i, R.cols()); ++j) R(i, j) = 0.0;
  }
  return R;
}

// The declared block holding `values` (first match), or null.
template <class Info>
const Info* Find(const std::vector<Info>& params, const double* values) {
  for (const Info& p : params) {
    if (p.values == values) return &p;
  }
  return nullptr;
}

}  // namespace

Marginalizer::Marginalizer(const MarginalizationOptions& options) : options_(options) {}

void Marginalizer::AddParameterBlock(double* values,
                                     int ambient_size,
                                     const ceres::Manifold* manifold,
                                     BlockRole role) {
  ParameterInfo p;
  p.values = values;
  p.ambient_size = ambient_size;
  p.tangent_size = manifold != nullptr ? manifold->TangentSize() : ambient_size;
  p.manifold = manifold;
  p.role = role;
  parameters_.push_back(p);
}

void Marginalizer::AddResidualBlock(const ceres::CostFunction* cost,
                                    const ceres::LossFunction* loss,
                                    std::vector<double*> parameter_blocks) {
  residuals_.push_back({cost, loss, std::move(parameter_blocks)});
}

MarginalizationStatus Marginalizer::AssignColumns(std::vector<ParameterInfo>* params_ptr,
                                                  MarginalizationResult* result) const {
  std::vector<ParameterInfo>& params = *params_ptr;
  for (size_t i = 0; i < params.size(); ++i) {
    const ParameterInfo& p = params[i];
    const bool bad_size = p.manifold != nullptr && p.manifold->AmbientSize() != p.ambient_size;
    const ParameterInfo* first = Find(params, p.values);
    if (p.values == nullptr || p.ambient_size <= 0 || bad_size || first != &params[i]) {
      return MarginalizationStatus::kBadBlock;
    }
  }
  // Which blocks the residuals touch, with their sizes checked against the cost functions.
  std::vector<bool> used(params.size(), false);
  for (const ResidualInfo& res : residuals_) {
    const std::vector<int32_t>& sizes = res.cost->parameter_block_sizes();
    if (sizes.size() != res.blocks.size()) return MarginalizationStatus::kBadBlock;
    for (size_t k = 0; k < res.blocks.size(); ++k) {
      const ParameterInfo* p = Find(params, res.blocks[k]);
      if (p == nullptr) return MarginalizationStatus::kUnknownBlock;
      if (p->ambient_size != sizes[k]) return MarginalizationStatus::kBadBlock;
      used[static_cast<size_t>(p - params.data())] = true;
    }
  }
  int offset = 0;
  for (BlockRole role : {BlockRole::kMarginalize, BlockRole::kKeep}) {
    for (size_t i = 0; i < params.size(); ++i) {
      if (!used[i] || params[i].role != role) continue;
      params[i].offset = offset;
      offset += params[i].tangent_size;
      if (role == BlockRole::kMarginalize) result->marginalized_dim += params[i].tangent_size;
      if (role == BlockRole::kKeep) result->kept_blocks.push_back(params[i].values);
    }
  }
  result->kept_dim = offset - result->marginalized_dim;
  return result->kept_dim == 0 ? MarginalizationStatus::kNothingToKeep : MarginalizationStatus::kOk;
}

bool Marginalizer::Linearize(const ResidualInfo& res,
                             const std::vector<ParameterInfo>& params,
                             Eigen::Index row,
                             Eigen::MatrixXd* J_all,
                             Eigen::VectorXd* r_all) {
  const int rows = res.cost->num_residuals();
  const size_t nb = res.blocks.size();
  std::vector<const ParameterInfo*> info(nb);
  std::vector<RowMajorMatrix> J_ambient(nb);
  std::vector<double*> J_ptr(nb, nullptr);
  for (size_t k = 0; k < nb; ++k) {
    info[k] = Find(params, res.blocks[k]);
    if (info[k]->offset < 0) continue;  // constant: evaluated, no columns
    J_ambient[k].resize(rows, info[k]->ambient_size);
    J_ptr[k] = J_ambient[k].data();
  }
  Eigen::VectorXd r(rows);
  if (!res.cost->Evaluate(res.blocks.data(), r.data(), J_ptr.data())) return false;
  if (!r.allFinite()) return false;
  std::vector<Eigen::MatrixXd> J(nb);
  for (size_t k = 0; k < nb; ++k) {
    if (J_ptr[k] == nullptr) continue;
    if (info[k]->manifold == nullptr) {
      J[k] = J_ambient[k];
    } else {
      RowMajorMatrix plus(info[k]->ambient_size, info[k]->tangent_size);
      if (!info[k]->manifold->PlusJacobian(res.blocks[k], plus.data())) return false;
      J[k] = J_ambient[k] * plus;
    }
    if (!J[k].allFinite()) return false;
  }
  if (res.loss != nullptr) ApplyLoss(*res.loss, &r, &J);
  r_all->segment(row, rows) = r;
  for (size_t k = 0; k < nb; ++k) {
    if (J[k].size() == 0) continue;
    J_all->block(row, info[k]->offset, rows, info[k]->tangent_size) += J[k];
  }
  return true;
}

// Square-root Schur complement (maths in marginalization_prior.h), with D the column scaling:
//   J_m D_m P_m = Q_m R_m   (rank ρ_m): rows ρ_m… of Q_mᵀ [J_k D_k, r] are [J', r']
//   J' P = Q R              (rank ρ):   J₀ = R_{0:ρ} Pᵀ D_k⁻¹,  r₀ = (Qᵀ r')_{0:ρ}
MarginalizationResult Marginalizer::Finish(const std::vector<ParameterInfo>& params,
                                           const Eigen::MatrixXd& J,
                                           const Eigen::VectorXd& r,
                                           MarginalizationResult result) const {
  const Eigen::Index m = result.marginalized_dim;
  const Eigen::Index n = result.kept_dim;
  const Eigen::VectorXd d = ColumnScaling(J);
  Eigen::MatrixXd kept(J.rows(), n + 1);
  kept << J.rightCols(n) * d.tail(n).asDiagonal(), r;
  Eigen::Index rank_m = 0;
  if (m > 0) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_m(J.leftCols(m) * d.head(m).asDiagonal());
    qr_m.setThreshold(options_.relative_rank_threshold);
    rank_m = qr_m.rank();
    kept.applyOnTheLeft(qr_m.householderQ().adjoint());
  }
  const Eigen::MatrixXd rest = kept.bottomRows(J.rows() - rank_m);
  if (rest.rows() == 0) {
    result.status = MarginalizationStatus::kNothingToKeep;
    return result;
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(rest.leftCols(n));
  qr.setThreshold(options_.relative_rank_threshold);
  result.rank = static_cast<int>(qr.rank());
  if (result.rank == 0) {
    result.status = MarginalizationStatus::kNothingToKeep;
    return result;
  }
  const Eigen::VectorXd qt_r = qr.householderQ().adjoint() * rest.col(n);
  Eigen::MatrixXd J0 = UpperRows(qr.matrixQR(), result.rank) * qr.colsPermutation().transpose() *
                       d.tail(n).cwiseInverse().asDiagonal();
  Eigen::VectorXd r0 = qt_r.head(result.rank);

  std::vector<MarginalizationPrior::Block> blocks;
  for (double* v : result.kept_blocks) {
    const ParameterInfo& p = *Find(params, v);
    MarginalizationPrior::Block b;
    b.manifold = p.manifold;
    b.x0 = Eigen::Map<const Eigen::VectorXd>(p.values, p.ambient_size);
    b.tangent_size = p.tangent_size;
    b.tangent_offset = p.offset - static_cast<int>(m);
    blocks.push_back(std::move(b));
  }
  result.prior =
      std::make_unique<MarginalizationPrior>(std::move(blocks), std::move(J0), std::move(r0));
  return result;
}

MarginalizationResult Marginalizer::Marginalize() const {
  MarginalizationResult result;
  std::vector<ParameterInfo> params = parameters_;
  result.status = AssignColumns(&params, &result);
  if (result.status != MarginalizationStatus::kOk) return result;
  Eigen::Index rows = 0;
  for (const ResidualInfo& res : residuals_) rows += res.cost->num_residuals();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, result.marginalized_dim + result.kept_dim);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(rows);
  Eigen::Index row = 0;
  for (const ResidualInfo& res : residuals_) {
    if (!Linearize(res, params, row, &J, &r)) {
      result.status = MarginalizationStatus::kEvaluationFailed;
      return result;
    }
    row += res.cost->num_residuals();
  }
  return Finish(params, J, r, std::move(result));
}

}  // namespace swlio::estimator

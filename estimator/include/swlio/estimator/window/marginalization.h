#pragma once
/// @file
/// Marginalization of the frames leaving the sliding window (issue 6): linearizes the residual
/// blocks that touch the dropped parameter blocks, Schur-complements the dropped blocks out
/// and returns a MarginalizationPrior over the kept ones (maths in marginalization_prior.h).
/// The Schur complement is taken in square-root form, by QR of the stacked Jacobian, never by
/// forming H = JᵀJ (see there for why).
///
/// Linearization, per residual block: ambient Jacobians from CostFunction::Evaluate, taken to
/// the tangent by Manifold::PlusJacobian; a robust loss ρ(s), s = |r|², is folded in as Ceres
/// does (Triggs et al., "Bundle adjustment — a modern synthesis", 2000, §4.3):
///   α = 1 − √(1 + 2 s ρ''/ρ'),  r ← √ρ' / (1 − α) · r,  J ← √ρ' (I − α r rᵀ / s) J
/// (α = 0 when s = 0 or ρ'' ≤ 0, i.e. plain √ρ' re-weighting). Blocks declared kConstant take
/// part in the evaluation only (no columns).
///
/// Usage, when the oldest frame leaves: declare every parameter block the chosen residuals
/// touch (its pose and speed_bias as kMarginalize, the rest kKeep or kConstant), add the
/// residual blocks that touch a dropped block (its IMU factor, its LiDAR factors, the previous
/// prior), call Marginalize(), then add result.prior over result.kept_blocks to the next
/// window. Cost functions and losses are only borrowed during Marginalize().

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>

#include <memory>
#include <vector>

#include "swlio/estimator/window/marginalization_prior.h"

namespace swlio::estimator {

enum class BlockRole { kMarginalize, kKeep, kConstant };

enum class MarginalizationStatus {
  kOk,
  kUnknownBlock,      ///< a residual uses a parameter block that was not declared
  kBadBlock,          ///< null/duplicate block, or size not matching its manifold
  kEvaluationFailed,  ///< a cost function returned false or a non-finite value
  kNothingToKeep,     ///< no kept block is touched, or the marginal carries no information
};

struct MarginalizationOptions {
  /// Rank decisions of the two column-pivoted QRs (marginalization_prior.h), on the Jacobian
  /// with unit-norm columns: |R_ii| ≤ this × max |R_ii| counts as zero. The rank-deficient
  /// directions carry no information; their round-off sits near 1e-16, the genuine directions
  /// of a window well above 1e-6. Must be in (0, 1).
  double relative_rank_threshold = 1e-10;
};

struct MarginalizationResult {
  MarginalizationStatus status = MarginalizationStatus::kOk;
  std::unique_ptr<MarginalizationPrior> prior;  ///< null unless kOk
  std::vector<double*> kept_blocks;             ///< the prior's parameter blocks, in order
  int marginalized_dim = 0;                     ///< tangent size eliminated
  int kept_dim = 0;                             ///< tangent size of kept_blocks
  int rank = 0;                                 ///< rows of the prior
};

class Marginalizer {
 public:
  explicit Marginalizer(const MarginalizationOptions& options = {});

  /// Declares a parameter block; `manifold` null for Euclidean (not owned; kept blocks' manifolds
  /// must outlive the prior).
  void AddParameterBlock(double* values,
                         int ambient_size,
                         const ceres::Manifold* manifold,
                         BlockRole role);

  /// A residual block over declared parameter blocks (`loss` may be null). Not owned.
  void AddResidualBlock(const ceres::CostFunction* cost,
                        const ceres::LossFunction* loss,
                        std::vector<double*> parameter_blocks);

  /// Linearizes at the current values of the blocks and builds the prior.
  MarginalizationResult Marginalize() const;

 private:
  struct ParameterInfo {
    double* values = nullptr;
    int ambient_size = 0;
    int tangent_size = 0;
    const ceres::Manifold* manifold = nullptr;
    BlockRole role = BlockRole::kKeep;
    int offset = -1;  ///< tangent column in H, −1 when not in H
  };
  struct ResidualInfo {
    const ceres::CostFunction* cost = nullptr;
    const ceres::LossFunction* loss = nullptr;
    std::vector<double*> blocks;
  };

  /// Validates the blocks and gives the touched ones their columns (dropped first).
  MarginalizationStatus AssignColumns(std::vector<ParameterInfo>* params,
                                      MarginalizationResult* result) const;
  /// Writes one linearized residual block into the rows of J (tangent columns) and r from `row`.
  static bool Linearize(const ResidualInfo& residual,
                        const std::vector<ParameterInfo>& params,
                        Eigen::Index row,
                        Eigen::MatrixXd* J,
                        Eigen::VectorXd* r);
  /// Square-root Schur complement of the stacked system into the prior.
  MarginalizationResult Finish(const std::vector<ParameterInfo>& params,
                               const Eigen::MatrixXd& J,
                               const Eigen::VectorXd& r,
                               MarginalizationResult result) const;

  MarginalizationOptions options_;
  std::vector<ParameterInfo> parameters_;
  std::vector<ResidualInfo> residuals_;
};

}  // namespace swlio::estimator

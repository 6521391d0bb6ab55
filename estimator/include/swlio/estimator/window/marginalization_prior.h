#pragma once
/// @file
/// The marginalization prior: what remains of the residuals of frames that left the window
/// (issue 6; the construction of VINS-Mono / LIO-Mapping, written anew here). Marginalizer
/// (marginalization.h) builds it; the window adds it as one more residual block.
///
/// The dropped residuals, linearized at x₀ in the tangent spaces of their blocks and stacked,
/// r + J δ with J = [J_m J_k] (dropped blocks m, kept blocks k), give the Gauss–Newton system
/// H = JᵀJ, b = Jᵀr. Eliminating δ_m gives the marginal over the kept tangent δ
///   H* = H_kk − H_km H_mm⁻¹ H_mk,   b* = b_k − H_km H_mm⁻¹ b_m,   cost ½ δᵀH*δ + b*ᵀδ + const.
/// We take it in square-root form (as in Demmel et al., "Square Root Marginalization for
/// Sliding-Window Bundle Adjustment", ICCV 2021): with the QR J_m = Q_m R_m, the rows of
/// Q_mᵀ[J_k, r] below rank(J_m), [J', r'], satisfy J'ᵀJ' = H*, J'ᵀr' = b*; a second QR
/// J' = Q R compresses them to ρ = rank(J') rows
///   J₀ = R_{0:ρ} (ρ × n),   r₀ = (Qᵀ r')_{0:ρ},   so J₀ᵀJ₀ = H*, J₀ᵀr₀ = b*.
/// Forming H first would square the condition number: whitened IMU rows reach 1e6 next to
/// LiDAR rows of ~50, and H* = H_kk − … then cancels down to round-off in the directions the
/// dropped frame did not constrain (relative eigenvalues ~1e-10 that are pure noise, measured on
/// the window test). Both QRs pivot columns and work on unit-norm columns, so ranks do not
/// depend on units; pseudo-inverse semantics where J_m is rank deficient.
/// The prior factor therefore returns
///   r(x) = r₀ + J₀ (x ⊟ x₀)         (⊟: Manifold::Minus of each kept block; x − x₀ if Euclidean)
/// and its Jacobian stays J₀ ("first-estimate Jacobian"): in each block's tangent at the current
/// x Ceres sees exactly J₀, handed over as the ambient Jacobian J₀ MinusJacobian(x), whatever x.
/// Holding it fixed keeps the information of the prior from changing with later estimates,
/// which would otherwise let it gain spurious information in unobservable directions.
///
/// @note The manifolds are not owned: they must outlive the prior (one static PoseManifold
/// is the intended use, with the Problem told DO_NOT_TAKE_OWNERSHIP).

#include <ceres/cost_function.h>
#include <ceres/manifold.h>

#include <Eigen/Core>
#include <vector>

namespace swlio::estimator {

class MarginalizationPrior final : public ceres::CostFunction {
 public:
  /// One kept parameter block with its linearization point.
  struct Block {
    const ceres::Manifold* manifold = nullptr;  ///< nullptr: Euclidean
    Eigen::VectorXd x0;                         ///< ambient value at linearization
    int tangent_size = 0;
    int tangent_offset = 0;  ///< first column of this block in J₀
  };

  /// `jacobian` is J₀ (ρ × Σ tangent sizes, ρ ≥ 1), `residual` is r₀ (ρ).
  MarginalizationPrior(std::vector<Block> blocks,
                       Eigen::MatrixXd jacobian,
                       Eigen::VectorXd residual);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const std::vector<Block>& blocks() const { return blocks_; }
  const Eigen::MatrixXd& jacobian() const { return jacobian_; }  ///< J₀
  const Eigen::VectorXd& residual() const { return residual_; }  ///< r₀

 private:
  const std::vector<Block> blocks_;
  const Eigen::MatrixXd jacobian_;
  const Eigen::VectorXd residual_;
};

}  // namespace swlio::estimator

#pragma once
/// @file
/// One frame's LiDAR term as a few linear rows (paper §4.3, eq. 17–18: the point-to-plane and
/// point-to-line residuals of the frame against the local map, linearized).
///
/// The robust Gauss–Newton system of the frame's residuals at a linearization point,
///   ½ δᵀHδ + bᵀδ (+ const),   δ = tangent of the frame's parameters (pose, optionally extrinsic),
/// is replaced by a Gaussian about its optimum δ* = −H⁺b:
///  - eigen-directions of H (H = V Λ Vᵀ) with λ < `min_eigenvalue` are left out: the scan does
///    not constrain them (Zhang, Kaess, Singh, "On degeneracy of optimization-based state
///    estimation problems", ICRA 2016) and the other factors (IMU, prior) carry them;
///  - in the kept directions V_k the covariance is Λ_k⁻¹ plus a floor F projected into them,
///    S = Λ_k⁻¹ + V_kᵀ F V_k, so that no frame claims more certainty than F however many
///    points it matched.
/// With S⁻¹ = L Lᵀ the rows are  r(δ) = U δ + r₀,  U = Lᵀ V_kᵀ,  r₀ = −U δ*.
/// Without a floor, ½|r(δ)|² = ½ δᵀHδ + bᵀδ + const exactly in the kept subspace.

#include <Eigen/Core>

namespace swlio::estimator {

struct LidarRows {
  Eigen::MatrixXd U;   ///< rows × n
  Eigen::VectorXd r0;  ///< rows
  int degenerate = 0;  ///< directions left out
};

/// H (n×n, symmetric), b (n), floor_covariance (n×n, symmetric positive semi-definite), all in
/// the units of the whitened residuals. No rows (U empty) when every direction is degenerate.
LidarRows CompressToRows(const Eigen::MatrixXd& H,
                         const Eigen::VectorXd& b,
                         const Eigen::MatrixXd& floor_covariance,
                         double min_eigenvalue);

}  // namespace swlio::estimator

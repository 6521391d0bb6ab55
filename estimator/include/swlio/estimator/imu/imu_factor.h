#pragma once
/// @file
/// IMU pre-integration factor between two window frames i and j (paper §4.3, eq. (21)):
///
///   r_B = [ R_nᵀ(p_{n+1} − p_n − v_n Δt − ½ gᵂ Δt²) − Δp
///           R_nᵀ(v_{n+1} − v_n − gᵂ Δt) − Δv
///           2[Δq⁻¹ ⊗ q_n⁻¹ ⊗ q_{n+1}]_xyz
///           b_{a,n+1} − b_{a,n}
///           b_{g,n+1} − b_{g,n} ]                                                   (21)
///
/// Implemented with imu_residual.h (Forster et al., TRO 2017, eq. (44)–(45)): the rotation row
/// is the exact Log(ΔR(b)ᵀ R_iᵀ R_j), which equals the paper's 2[·]_xyz to first order, and Δ·
/// are corrected to frame i's biases to first order. Rows (15), in the order of the covariance:
///   [r_ΔR; r_Δv; r_Δp; r_bg; r_ba],  r_bg = b_g,j − b_g,i,  r_ba = b_a,j − b_a,i.
/// Weighting (the paper leaves (20) unweighted; issue 6 weights by the pre-integrated
/// covariance): the factor returns W r with Wᵀ W = Σ⁻¹,
///   Σ = blockdiag(PreintegratedImu::covariance, BiasWalkCovariance(noise, Δt)).
///
/// Parameter blocks, in this order:
///   pose_i[7], speed_bias_i[9], pose_j[7], speed_bias_j[9]
///   pose = [p_world; q_world_imu (x, y, z, w)]   with PoseManifold (pose_manifold.h)
///   speed_bias = [v_world; bias_acc; bias_gyro]   Euclidean (m/s, m/s², rad/s)
/// Pose Jacobians are J_δ·M(q) (pose_manifold.h) with J_δ from ImuResidualJacobians.
///
/// @note The factor keeps the pre-integration it was created with. When frame i's biases move
/// past Preintegrator::NeedsReintegration, the caller re-integrates and builds a new factor.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <memory>

#include "swlio/estimator/common/estimator_config.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {

inline constexpr int kSpeedBiasSize = 9;
/// Offsets inside a speed_bias block.
inline constexpr int kSbVel = 0;
inline constexpr int kSbBiasAcc = 3;
inline constexpr int kSbBiasGyro = 6;
/// Rows of the bias random-walk residual (after the 9 pre-integration rows).
inline constexpr int kRowBiasGyro = 9;
inline constexpr int kRowBiasAcc = 12;
inline constexpr int kImuFactorResiduals = 15;

using Mat15 = Eigen::Matrix<double, kImuFactorResiduals, kImuFactorResiduals>;

class ImuFactor final
    : public ceres::SizedCostFunction<kImuFactorResiduals, 7, kSpeedBiasSize, 7, kSpeedBiasSize> {
 public:
  /// Nothing when Σ is not positive definite (an empty interval, zero noise densities).
  static std::unique_ptr<ImuFactor> Create(const PreintegratedImu& pim,
                                           const ImuNoiseConfig& noise,
                                           double gravity_mps2);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const PreintegratedImu& preintegrated() const { return pim_; }
  /// W = L⁻¹ for Σ = L Lᵀ (lower triangular), so Wᵀ W = Σ⁻¹.
  const Mat15& sqrt_information() const { return sqrt_information_; }

 private:
  ImuFactor(const PreintegratedImu& pim, double gravity_mps2, const Mat15& sqrt_information);

  const PreintegratedImu pim_;
  const Eigen::Vector3d gravity_world_;
  const Mat15 sqrt_information_;
};

}  // namespace swlio::estimator

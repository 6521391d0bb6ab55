#pragma once
/// @file
/// Relative-pose (between) factor of the pose graph (issue 8; the paper's loop closure, §2):
/// a measured T_ij = (R_m, p_m) between the IMU poses of two keyframes, T_world_i = (R_i, p_i)
/// and T_world_j = (R_j, p_j):
///
///   r_p = R_iᵀ (p_j − p_i) − p_m                 (position of j seen from i, minus the measured)
///   r_φ = Log(R_mᵀ R_iᵀ R_j)                     (rotation error, radians)
///   r   = S [r_p; r_φ]                            (S: 6×6 square-root information)
///
/// Jacobians in the tangents of pose_manifold.h (p ← p + δp, R ← R Exp(δφ)):
///   ∂r_p/∂δp_i = −R_iᵀ,  ∂r_p/∂δφ_i = [R_iᵀ (p_j − p_i)]×,  ∂r_p/∂δp_j = R_iᵀ,  ∂r_p/∂δφ_j = 0
///   ∂r_φ/∂δφ_j = J_r⁻¹(r_φ),  ∂r_φ/∂δφ_i = −J_r⁻¹(r_φ) R_jᵀ R_i,  ∂r_φ/∂δp = 0
/// (R_i Exp(δ) gives R_mᵀ Exp(−δ) R_iᵀ R_j = E Exp(−R_jᵀ R_i δ) with E = R_mᵀ R_iᵀ R_j);
/// ambient Jacobians J_δ M(q) as in pose_manifold.h.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>

namespace swlio::estimator {

using Mat6 = Eigen::Matrix<double, 6, 6>;

class RelativePoseFactor final : public ceres::SizedCostFunction<6, 7, 7> {
 public:
  /// `T_i_j`: the measured pose of j in i's frame; `sqrt_information` S (6×6, rows act on
  /// [r_p (m); r_φ (rad)]). Null when S is not finite.
  static std::unique_ptr<RelativePoseFactor> Create(const Eigen::Isometry3d& T_i_j,
                                                    const Mat6& sqrt_information);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  RelativePoseFactor(const Eigen::Isometry3d& T_i_j, const Mat6& sqrt_information);

  const Eigen::Matrix3d R_m_;
  const Eigen::Vector3d p_m_;
  const Mat6 sqrt_information_;
};

/// Diagonal square-root information for position σ_p (m) and rotation σ_r (rad).
Mat6 DiagonalSqrtInformation(double sigma_position_m, double sigma_rotation_rad);

}  // namespace swlio::estimator

#pragma once
/// @file
/// Point-to-line factor: an edge feature x of window frame α against a line of the local map
/// (the edge counterpart of the paper's eq. (18), §4.3; frames as in point_to_plane_factor.h,
/// the local map in the world frame rather than in scan p's frame of eq. (17)).
///
/// With the line (unit direction d, centroid c) and B = [b₁ b₂] an orthonormal basis of the
/// plane orthogonal to d (fixed at construction):
///   y = R_e x + t_e,   w = R y + p
///   r = s · Bᵀ (w − c)        (2 rows; |r|² = s² |(I − d dᵀ)(w − c)|², scan_matcher.h's
///                              3-row distance, without its rank deficiency)
/// Jacobians (tangents of pose_manifold.h):
///   ∂r/∂δp = s Bᵀ,  ∂r/∂δφ = −s Bᵀ R [y]×,  ∂r/∂δt_e = s Bᵀ R,  ∂r/∂δφ_e = −s Bᵀ R R_e [x]×
///
/// Parameter blocks: pose_world_imu[7] of frame α, extrinsic T_imu_lidar[7] (PoseManifold).
/// The caller adds a robust loss.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <memory>

namespace swlio::estimator {

class PointToLineFactor final : public ceres::SizedCostFunction<2, 7, 7> {
 public:
  /// `point_lidar`: feature in the LiDAR frame (m); `direction_world` (normalized here, must be
  /// non-zero) and `centroid_world` (m): the map line; `sqrt_information` (1/m) > 0.
  static std::unique_ptr<PointToLineFactor> Create(const Eigen::Vector3d& point_lidar,
                                                   const Eigen::Vector3d& direction_world,
                                                   const Eigen::Vector3d& centroid_world,
                                                   double sqrt_information = 1.0);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  PointToLineFactor(const Eigen::Vector3d& point_lidar,
                    const Eigen::Matrix<double, 2, 3>& basis_t,
                    const Eigen::Vector3d& centroid_world);

  const Eigen::Vector3d point_lidar_;
  const Eigen::Matrix<double, 2, 3> basis_t_;  ///< s · Bᵀ
  const Eigen::Vector3d centroid_world_;
};

}  // namespace swlio::estimator

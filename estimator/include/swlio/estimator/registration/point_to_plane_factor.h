#pragma once
/// @file
/// Point-to-plane factor: a planar feature x of window frame α against a plane of the local
/// map (paper §4.3, eq. (17)–(18)):
///
///   T_{Lα}^{Lp} = T_B^L (T_{Bp}^W)⁻¹ T_{Bα}^W (T_B^L)⁻¹                                    (17)
///   r_L = ωᵀ (R_{Lα}^{Lp} x + t_{Lα}^{Lp}) [+ d]                                           (18)
///
/// The paper keeps the local map in the LiDAR frame of the window's first scan p (17); we keep
/// it in the world frame, a fixed change of coordinates that leaves the cost unchanged and
/// keeps pose_p out of every residual. With T_world_imu = (R, p), T_imu_lidar = (R_e, t_e) and
/// the plane (unit normal n, centroid c, so d = −nᵀc):
///   y = R_e x + t_e           (feature in the IMU frame)
///   w = R y + p               (feature in the world frame)
///   r = s · nᵀ (w − c)        (s = sqrt-information, 1/σ in 1/m)
/// Jacobians in the tangents of pose_manifold.h (R ← R Exp(δφ), p ← p + δp; same for R_e, t_e):
///   ∂w/∂δp = I,  ∂w/∂δφ = −R [y]×,  ∂w/∂δt_e = R,  ∂w/∂δφ_e = −R R_e [x]×
///   ∂r/∂(·) = s nᵀ ∂w/∂(·);  ambient Jacobians J_δ M(q) as in pose_manifold.h.
///
/// Parameter blocks: pose_world_imu[7] of frame α, extrinsic T_imu_lidar[7] (both PoseManifold;
/// hold the extrinsic constant when it is not estimated online). The caller adds a robust loss.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <memory>

namespace swlio::estimator {

class PointToPlaneFactor final : public ceres::SizedCostFunction<1, 7, 7> {
 public:
  /// `point_lidar`: feature in the LiDAR frame (m); `normal_world` (normalized here) and
  /// `centroid_world` (m): the map plane; `sqrt_information` (1/m) > 0.
  static std::unique_ptr<PointToPlaneFactor> Create(const Eigen::Vector3d& point_lidar,
                                                    const Eigen::Vector3d& normal_world,
                                                    const Eigen::Vector3d& centroid_world,
                                                    double sqrt_information = 1.0);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  PointToPlaneFactor(const Eigen::Vector3d& point_lidar,
                     const Eigen::Vector3d& normal_world,
                     const Eigen::Vector3d& centroid_world,
                     double sqrt_information);

  const Eigen::Vector3d point_lidar_;
  const Eigen::Vector3d normal_world_;
  const Eigen::Vector3d centroid_world_;
  const double sqrt_information_;
};

}  // namespace swlio::estimator

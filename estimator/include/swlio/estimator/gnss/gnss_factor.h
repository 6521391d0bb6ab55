#pragma once
/// @file
/// GNSS position factor of the pose graph (issue 8): a fix z (the antenna in the local ENU
/// frame, gnss_config.h) on one keyframe node T_map_imu = (R, p), through the alignment of the
/// map frame to ENU, T_enu_map = (Rz(ψ), t) (4 DoF: both frames are gravity-aligned, so only
/// yaw and translation are free), and the antenna's position b in the node's IMU frame (the
/// lever arm, moved by the odometry between the node and the fix's time: gnss_associator.h):
///
///   r = S (Rz(ψ) (p + R b) + t − z),      S = diag(1/σ_h, 1/σ_h, 1/σ_v)
///
/// Jacobians in the tangents (pose_manifold.h: p ← p + δp, R ← R Exp(δφ)):
///   ∂r/∂δp = S Rz,   ∂r/∂δφ = −S Rz R [b]×,   ∂r/∂ψ = S Rz [e_z]× (p + R b),   ∂r/∂t = S.
/// Alignment block: [ψ, t_x, t_y, t_z] (4 doubles, Euclidean).

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>

#include "swlio/estimator/common/pose_manifold.h"

namespace swlio::estimator {

inline constexpr int kEnuAlignmentSize = 4;
using EnuAlignment = std::array<double, kEnuAlignmentSize>;  ///< [ψ (rad), t_x, t_y, t_z (m)]

/// T_enu_map of an alignment block.
Eigen::Isometry3d EnuFromAlignment(const double* alignment);

class GnssPositionFactor final : public ceres::SizedCostFunction<3, kPoseSize, kEnuAlignmentSize> {
 public:
  /// Null when a value is not finite or a σ is not positive.
  static std::unique_ptr<GnssPositionFactor> Create(const Eigen::Vector3d& antenna_imu_m,
                                                    const Eigen::Vector3d& fix_enu_m,
                                                    double sigma_h_m,
                                                    double sigma_v_m);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  /// Whitened squared residual at the given blocks.
  double Chi2(const double* pose, const double* alignment) const;

 private:
  GnssPositionFactor(const Eigen::Vector3d& antenna_imu_m,
                     const Eigen::Vector3d& fix_enu_m,
                     double sigma_h_m,
                     double sigma_v_m);

  const Eigen::Vector3d b_;
  const Eigen::Vector3d z_;
  const Eigen::Vector3d sqrt_info_;
};

}  // namespace swlio::estimator

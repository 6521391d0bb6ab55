#pragma once
/// @file
/// The pose parameter block of the window optimization and its Ceres manifold.
///
/// Storage (7 doubles): x = [p_x, p_y, p_z, q_x, q_y, q_z, q_w] for T_parent_child = (R(q), p):
/// p in metres in the parent frame, q a unit Hamilton quaternion in Eigen's storage order
/// (x, y, z, w). Used for T_world_imu of every window frame and for the extrinsic T_imu_lidar.
///
/// Tangent (6): δ = [δp; δφ], the perturbation stated in imu_residual.h:
///   Plus:   p ⊞ δ = p + δp,            q ⊞ δ = q ⊗ Exp(δφ)     (R ← R Exp(δφ))
///   Minus:  y ⊟ x = [p_y − p_x;  Log(q_x⁻¹ ⊗ q_y)]
/// Jacobians at δ = 0 (rows/columns in storage order; q = (w, v)):
///   ∂(x ⊞ δ)/∂δ = [I 0; 0 Q],  Q (4×3) = ½ [w I + [v]×; −vᵀ]      (q ⊗ [1; ½δφ])
///   ∂(y ⊟ x)/∂y |_{y=x} = [I 0; 0 M],  M (3×4) = 2 [w I − [v]×, −v]  (Log ≈ 2·vec near I)
/// and M Q = (w² + |v|²) I = I, as Ceres requires.
///
/// Residuals of this library take Jacobians in the tangent δ (J_δ, the maths above each
/// factor) and hand Ceres the ambient Jacobian J_x = J_δ M(q). Every residual reads the
/// rotation from the normalized quaternion, so it does not change along q (the radial
/// direction, where M q = 0) and J_x is its exact ambient derivative at unit q; Ceres then
/// forms J_x Q = J_δ.

#include <ceres/manifold.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace swlio::estimator {

inline constexpr int kPoseSize = 7;         ///< ambient size of a pose block
inline constexpr int kPoseTangentSize = 6;  ///< tangent size of a pose block

using PosePlusJacobian = Eigen::Matrix<double, kPoseSize, kPoseTangentSize, Eigen::RowMajor>;
using PoseMinusJacobian = Eigen::Matrix<double, kPoseTangentSize, kPoseSize, Eigen::RowMajor>;

/// The pose stored in a 7-double block (the quaternion is normalized).
Eigen::Isometry3d PoseFromParameters(const double* x);

/// Writes `T` into a 7-double block.
void PoseToParameters(const Eigen::Isometry3d& T, double* x);

/// ∂(x ⊞ δ)/∂δ at δ = 0.
PosePlusJacobian PosePlusJacobianAt(const double* x);

/// ∂(y ⊟ x)/∂y at y = x; also the map from tangent to ambient Jacobians (J_x = J_δ M).
PoseMinusJacobian PoseMinusJacobianAt(const double* x);

/// Ceres manifold of a pose block; stateless, so one instance can serve every block (give the
/// Problem DO_NOT_TAKE_OWNERSHIP in that case).
class PoseManifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseSize; }
  int TangentSize() const override { return kPoseTangentSize; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace swlio::estimator

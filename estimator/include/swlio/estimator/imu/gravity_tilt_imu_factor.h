#pragma once
/// @file
/// An ImuFactor (imu_factor.h) between frames stated in a map frame whose gravity direction is
/// estimated: the tilt θ = [θx, θy] of the map against gravity is one more parameter block.
///
/// Why: at a standing start the accelerometer bias and the tilt are one unknown (the
/// initializer gives the tilt that zeroes the horizontal bias), so the first map is built tilted
/// by b_a,h / g. Once a turn makes b_a observable, an estimator whose map frame is gravity
/// aligned by definition either tilts the new frames against the old map, or keeps the map and
/// carries a bias that would have to change with the heading. Estimating where gravity points
/// in the map frame instead keeps the map rigid and the IMU consistent (measured on loop943:
/// ARCHITECTURE.md, "The map's tilt against gravity").
///
/// With Q = Exp([θx, θy, 0]) (map → gravity-aligned frame) the residual is the ImuFactor's at
///   p' = Q p,  q' = q_Q ⊗ q,  v' = Q v   (biases unchanged),
/// which equals the ImuFactor with gravity Qᵀ gᵂ in the map frame. Parameter blocks:
///   pose_i[7], speed_bias_i[9], pose_j[7], speed_bias_j[9], tilt[2]
/// Pose and velocity Jacobians are chained exactly (∂q'/∂q = L(q_Q), the left-product matrix,
/// which maps the PoseManifold's right perturbation of q to that of q'); the tilt Jacobian is a
/// central difference (θ is a fraction of a degree, the residual smooth in it).

#include <ceres/sized_cost_function.h>

#include <Eigen/Geometry>

#include "swlio/estimator/imu/imu_factor.h"

namespace swlio::estimator {

inline constexpr int kGravityTiltSize = 2;

/// Q = Exp([θx, θy, 0]): rotates map-frame vectors into the gravity-aligned frame.
Eigen::Quaterniond GravityTiltRotation(const double* tilt);

class GravityTiltImuFactor final : public ceres::SizedCostFunction<kImuFactorResiduals,
                                                                   7,
                                                                   kSpeedBiasSize,
                                                                   7,
                                                                   kSpeedBiasSize,
                                                                   kGravityTiltSize> {
 public:
  /// `imu` is not owned and must outlive this factor.
  explicit GravityTiltImuFactor(const ImuFactor* imu) : imu_(imu) {}

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const ImuFactor* imu() const { return imu_; }

 private:
  /// The ImuFactor's residual (and, where asked, its Jacobians) at the states moved by Q.
  bool EvaluateRotated(double const* const* parameters,
                       const double* tilt,
                       double* residuals,
                       double** jacobians) const;

  const ImuFactor* imu_;
};

}  // namespace swlio::estimator

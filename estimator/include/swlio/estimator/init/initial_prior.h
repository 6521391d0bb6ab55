#pragma once
/// @file
/// The covariance of the window's first state after an initialization that found "up" with the
/// accelerometer (StaticInitializer standing, DynamicInitializer moving).
///
/// The accelerometer measures f = Rᵀ g_w + b_a at rest (g_w = [0, 0, g]; the same holds for the
/// gravity part of a moving alignment). It fixes the sum, not the parts: a bias b_a across the
/// up axis u = Rᵀ e_z reads exactly like a tilt. With R ← R Exp(δφ) (pose_manifold.h),
///   δf = g [u]× δφ + δb_a,
/// so after the initialization (δf = n, its own noise)
///   δφ = (1/g) [u]× (δb_a − n) + u δψ      (tilt follows the bias; δψ the yaw gauge).
/// With independent δp, δψ, n, δv, δb_a, δb_g of the given standard deviations this gives the
/// 15×15 covariance over [δp; δφ; δv; δb_a; δb_g] (the tangent of the first frame's pose and
/// speed_bias blocks). A diagonal prior with a small tilt σ claims the tilt is known to the
/// accelerometer noise while the bias is not: measured on the `short` drive, the first state's
/// tilt was 2.4 mrad off with 1 mrad claimed, and the error was held for 40 s.

#include <Eigen/Core>

namespace swlio::estimator {

struct InitialStdDevs {
  double position_m = 1e-3;
  double yaw_rad = 1e-3;
  double tilt_measured_rad = 1e-3;  ///< n / g: the gravity direction as measured
  double velocity_mps = 0.05;
  double bias_acc_mps2 = 0.05;
  double bias_gyro_radps = 0.005;
};

/// Σ over [δp; δφ; δv; δb_a; δb_g] (15×15) for the first state with rotation R_world_imu.
Eigen::Matrix<double, 15, 15> InitialCovariance(const Eigen::Matrix3d& R_world_imu,
                                                double gravity_mps2,
                                                const InitialStdDevs& sigma);

}  // namespace swlio::estimator

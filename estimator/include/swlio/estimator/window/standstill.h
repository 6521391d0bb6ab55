#pragma once
/// @file
/// Standstill (zero-velocity) detection for the window: a frame whose IMU interval shows a
/// robot at rest, and whose LiDAR registration agrees, gets a zero-velocity factor.
///
/// Why: a robot stopped at an inspection point in a LiDAR-degenerate place (a corridor
/// between walls, an open yard) has directions the scan does not constrain; the window leaves
/// them to the IMU, which integrates its bias error. Measured on `short` seed 1 with a 60 s
/// standing start: the pose wandered 14–22 cm along the road while the robot stood still.
/// At rest the velocity is known exactly, which bounds that drift (the classic ZUPT of
/// pedestrian and vehicle inertial navigation).
///
/// The IMU test over the samples of the frame's interval (at rest the accelerometer reads
/// f = R_gᵀ (0, 0, g) + b_a and the gyro ω = b_g, R_g the IMU attitude against gravity):
/// - per-axis standard deviation of f ≤ max_acc_std_mps2 and of ω ≤ max_gyro_std_radps;
/// - |mean f − b_a − R_gᵀ (0, 0, g)| ≤ max_specific_force_error_mps2 (no acceleration, which
///   the estimated attitude and bias make visible, unlike at the static initialization);
/// - |mean ω − b_g| ≤ max_rate_radps (no turning).
/// A constant-velocity straight drive passes these (an IMU cannot tell it from rest), so the
/// LiDAR must agree: the sweep's own registration may have moved at most
/// max_lidar_speed_mps × Δt from the window's oldest frame.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"
#include "swlio/estimator/imu/imu_factor.h"

namespace swlio::estimator {

struct StandstillConfig {
  bool enabled = true;
  /// MTi-G-710 at 400 Hz: 0.012 m/s² and 0.0035 rad/s of white noise per axis at rest (the
  /// StaticInitializer's limits, which leave room for fans and pumps on a parked robot).
  double max_acc_std_mps2 = 0.03;
  double max_gyro_std_radps = 0.01;
  /// 0.05 m/s² ≈ 0.3° of tilt error, well above a converged attitude's.
  double max_specific_force_error_mps2 = 0.05;
  double max_rate_radps = 0.005;  ///< 0.3 °/s
  /// Registration jitter at rest is ≈ 1 cm per sweep; a crawl slower than this with no
  /// acceleration at all would be taken for rest.
  double max_lidar_speed_mps = 0.1;
  double sigma_velocity_mps = 0.005;  ///< of the zero-velocity factor, per axis

  ConfigIssues Validate() const;
};

/// The IMU test above over `samples` (the frame's interval). `R_gravity_imu` is the IMU
/// attitude in a gravity-aligned frame (z up), `bias_acc`/`bias_gyro` the current estimates.
/// False with fewer than 4 samples.
bool ImuAtRest(const std::vector<ImuSample>& samples,
               const Eigen::Matrix3d& R_gravity_imu,
               const Eigen::Vector3d& bias_acc,
               const Eigen::Vector3d& bias_gyro,
               double gravity_mps2,
               const StandstillConfig& config);

/// r = v / σ on a frame's speed-bias block (velocity in the world frame; zero at rest).
class ZeroVelocityFactor final : public ceres::SizedCostFunction<3, kSpeedBiasSize> {
 public:
  explicit ZeroVelocityFactor(double sigma_mps) : inv_sigma_(1.0 / sigma_mps) {}

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  double inv_sigma_;
};

}  // namespace swlio::estimator

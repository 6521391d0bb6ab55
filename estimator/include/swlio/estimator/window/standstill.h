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
/// The IMU test over the last `imu_window_s` of samples up to the frame (at rest the
/// accelerometer reads f = R_gᵀ (0, 0, g) + b_a and the gyro ω = b_g, R_g the IMU attitude
/// against gravity), with the vibration-proof statistics of imu_stillness.h:
/// - per-axis standard deviation of f low-passed below the vibration band ≤ max_acc_std_mps2
///   and of ω ≤ max_gyro_std_radps (a push, a start or a stop; chassis vibration at 15–80 Hz
///   is filtered out);
/// - |mean f − b_a − R_gᵀ (0, 0, g)| ≤ max_specific_force_error_mps2 (no acceleration, which
///   the estimated attitude and bias make visible, unlike at the static initialization);
/// - |mean ω − b_g| ≤ max_rate_radps (no turning);
/// with Hann-weighted means. A constant-velocity straight drive passes these (an IMU cannot
/// tell it from rest), so the LiDAR must agree: the sweep's own registration may have moved at
/// most max_lidar_speed_mps × Δt from the window's oldest frame. The zero-velocity factor's
/// standard deviation is the larger of sigma_velocity_mps and the measured velocity RMS about
/// rest (vibration keeps the velocity from being exactly zero).

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"
#include "swlio/estimator/imu/imu_factor.h"

namespace swlio::estimator {

struct StandstillConfig {
  bool enabled = true;
  /// Samples tested: this much IMU time up to the frame (at least the frame's interval). 0.5 s
  /// holds 7.5 periods of the slowest vibration (15 Hz), whose Hann-weighted mean then leaks
  /// < 1e-3 of its amplitude.
  double imu_window_s = 0.5;
  /// Of the low-passed signals (imu_stillness.h). MTi-G-710 white noise at 400 Hz (0.012 m/s²,
  /// 0.0035 rad/s per sample) leaves 0.002 m/s² and 0.0006 rad/s after it, 2 m/s² RMS of
  /// vibration at 16–73 Hz 0.011 m/s² (tests/estimator/window/standstill_test.cpp); the
  /// StaticInitializer's limits.
  double max_acc_std_mps2 = 0.02;
  double max_gyro_std_radps = 0.01;
  /// 0.05 m/s² ≈ 0.3° of tilt error, well above a converged attitude's.
  double max_specific_force_error_mps2 = 0.05;
  double max_rate_radps = 0.005;  ///< 0.3 °/s
  /// Registration jitter at rest is ≈ 1 cm per sweep; a crawl slower than this with no
  /// acceleration at all would be taken for rest.
  double max_lidar_speed_mps = 0.1;
  /// Floor of the zero-velocity factor's standard deviation, per axis (the measured velocity
  /// RMS about rest is used when larger).
  double sigma_velocity_mps = 0.005;

  ConfigIssues Validate() const;
};

/// The IMU test above over `samples` (the last imu_window_s up to the frame). `R_gravity_imu`
/// is the IMU attitude in a gravity-aligned frame (z up), `bias_acc`/`bias_gyro` the current
/// estimates. Nothing when the IMU shows motion or there are fewer than 4 samples; else the
/// zero-velocity factor's standard deviation (m/s).
std::optional<double> ImuAtRest(const std::vector<ImuSample>& samples,
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

#pragma once
/// @file
/// Static initialization from a standing start: gravity direction (R_world_imu with yaw = 0),
/// gyro bias and the observable part of the accelerometer bias, from IMU samples buffered over
/// `EstimatorConfig::init_static_duration_s` of stillness plus the stillness test's 0.2 s
/// low-pass kernel (imu_stillness.h).
///
/// At rest the accelerometer reads f = R_world_imuᵀ (0, 0, g) + b_a + noise and the gyro
/// ω = b_g + noise (Earth rate, 7.3e-5 rad/s, is absorbed into b_g). So over a still window:
/// - b_g = mean(ω), with standard error σ_ω/√N;
/// - the gravity direction in the IMU frame is mean(f)/|mean(f)|, giving roll and pitch
///   (yaw is unobservable and set to 0: world x is the IMU's initial heading);
/// - b_a is observable only along gravity: b_a ≈ (|mean f| − g) · mean(f)/|mean f|. Its
///   horizontal part cannot be separated from a tilt: it shows up as a roll/pitch error of
///   about |b_a,horizontal|/g rad (0.02 m/s² → 0.12°) and is left to the sliding window.
///
/// Stillness test over the window (thresholds in Options), with the vibration-proof statistics
/// of imu_stillness.h (Hann-weighted means, spreads of the signals low-passed below the
/// vibration band, so that motors idling at 0.5–2 m/s² RMS do not read as motion):
/// - low-passed std(acc) ≤ max_acc_std_mps2 and std(gyro) ≤ max_gyro_std_radps (a push, a
///   start, a rocking robot);
/// - | |mean f| − g | ≤ max_gravity_error_mps2 (sustained linear acceleration);
/// - |mean ω| ≤ max_gyro_mean_radps (a steady turn);
/// - |mean f over the window's second half − over its first half| ≤ max_acc_drift_mps2 (a
///   smooth speed change: 0.3 m/s² of acceleration would otherwise pass as a 1.75° tilt), and
///   the same for ω ≤ max_gyro_drift_radps (the tail of a turn would bias b_g).
/// A constant-velocity straight drive is indistinguishable from rest for an IMU alone.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <string_view>

#include "swlio/core/types.h"
#include "swlio/estimator/common/estimator_config.h"

namespace swlio::estimator {

enum class InitStatus {
  kCollecting,  ///< not yet initialized: less than the required still duration buffered
  kMoving,      ///< not yet initialized: the current window fails the stillness test
  kBadTime,     ///< not yet initialized: a sample went back in time (the buffer was reset)
  kInitialized,
};

/// Human-readable reason for a status.
std::string_view InitStatusReason(InitStatus status);

struct StaticInitResult {
  InitStatus status = InitStatus::kCollecting;
  /// Valid when initialized: t_ns = last sample, R_world_imu gravity-aligned with yaw 0,
  /// p = 0, v = 0, bias_gyro, bias_acc (gravity-axis part only).
  State state;
  Eigen::Vector3d gravity_imu = Eigen::Vector3d::Zero();  ///< unit, "up" in the IMU frame
  /// Window statistics (whatever window was last tested).
  double window_s = 0.0;
  double acc_std_mps2 = 0.0;            ///< largest per-axis standard deviation (vibration)
  double gyro_std_radps = 0.0;          ///< largest per-axis standard deviation
  double velocity_excursion_mps = 0.0;  ///< imu_stillness.h
  double angle_excursion_rad = 0.0;
  double gravity_error_mps2 = 0.0;  ///< |mean f| − g
  double gyro_mean_radps = 0.0;     ///< |mean ω|
  double acc_drift_mps2 = 0.0;      ///< |mean f (second half) − mean f (first half)|
  double gyro_drift_radps = 0.0;    ///< the same for ω
  Eigen::Vector3d bias_gyro_std = Eigen::Vector3d::Zero();  ///< standard error of b_g
};

class StaticInitializer {
 public:
  struct Options {
    /// Per-axis std of the specific force low-passed below the vibration band (0.2 s Hann
    /// means). MTi-G-710 white noise leaves 0.002 m/s², 2 m/s² RMS of vibration at 16–73 Hz
    /// 0.011; `aggressive`'s start (0.9 m/s², nearly constant, which an IMU alone takes for a
    /// 5° tilt) 0.0295 over a 1 s window.
    double max_acc_std_mps2 = 0.02;
    /// The same for the rate: white noise leaves 0.0006 rad/s; 0.01 ≈ 0.6 °/s.
    double max_gyro_std_radps = 0.01;
    /// | |mean f| − g |: allows a 0.3 m/s² accelerometer scale/bias error, no more.
    double max_gravity_error_mps2 = 0.3;
    /// |mean ω|: MTi gyro biases are ≪ 1 °/s; 0.03 rad/s ≈ 1.7 °/s rules out a slow turn.
    double max_gyro_mean_radps = 0.03;
    /// Half-window mean difference of f: white noise alone gives 0.0012 m/s² per axis (1σ,
    /// 1 s at 400 Hz); 0.01 m/s² ≈ 0.06° of tilt.
    double max_acc_drift_mps2 = 0.01;
    /// Half-window mean difference of ω: white noise gives 0.00035 rad/s per axis (1σ).
    double max_gyro_drift_radps = 0.002;
  };

  explicit StaticInitializer(const EstimatorConfig& config);
  StaticInitializer(const EstimatorConfig& config, const Options& options);

  /// Adds one sample (time-ordered) and re-tests the most recent window. Once initialized the
  /// result is frozen; Reset() starts over.
  const StaticInitResult& Add(const ImuSample& sample);

  const StaticInitResult& result() const { return result_; }
  bool initialized() const { return result_.status == InitStatus::kInitialized; }
  void Reset();

 private:
  void Evaluate();

  double gravity_mps2_;
  int64_t duration_ns_;
  Options options_;
  std::deque<ImuSample> window_;
  StaticInitResult result_;
};

}  // namespace swlio::estimator

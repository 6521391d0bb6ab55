#pragma once
/// @file
/// Stillness statistics of a run of IMU samples that a vibrating chassis does not fool (issue
/// 36): the shared measurements of the static initialization and of standstill detection.
///
/// A robot standing with its motors idling shakes at 15–80 Hz with 0.5–2 m/s² RMS. The
/// per-axis standard deviation of the specific force then says nothing about motion (it is the
/// vibration's RMS), and a plain mean over a window that holds a non-whole number of periods
/// keeps up to A/(π f T) of a tone of amplitude A (0.3 m/s² at 15 Hz over 0.1 s). So:
/// - means are weighted with a Hann window: a tone of n ≥ 3 periods in the window leaks
///   |sinc(n)/(1 − n²)| of its amplitude (< 1e-3 at n = 7.5, i.e. 15 Hz over 0.5 s);
/// - motion is judged by the spread of the signal low-passed below the vibration band: Hann
///   means over 0.2 s, every 25 ms across the window (a Hann kernel of T passes 80 % at
///   0.4/T = 2 Hz, where starts, stops and pushes are, and < 1 % at 3.5/T = 17.5 Hz and
///   above, where chassis vibration is);
/// - the velocity excursion is how far the integral of (f − mean f) strays from its own mean
///   (a tone of amplitude A at f moves the velocity by A/(2πf): 0.03 m/s for 2.8 m/s² at
///   15 Hz). Its RMS is the velocity's spread about rest: the zero-velocity factor's noise,
///   measured instead of assumed.

#include <Eigen/Core>
#include <span>

#include "swlio/core/types.h"

namespace swlio::estimator {

/// The low-pass kernel's length (s): Hann means over this much time.
inline constexpr double kStillLowpassWindowS = 0.2;

struct ImuStillness {
  Eigen::Vector3d acc_mean_mps2 = Eigen::Vector3d::Zero();    ///< Hann-weighted
  Eigen::Vector3d gyro_mean_radps = Eigen::Vector3d::Zero();  ///< Hann-weighted
  /// Hann-weighted means over the first and the second half (a slow speed change or the end of
  /// a turn shows as a difference).
  Eigen::Vector3d acc_first_half_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d acc_second_half_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_first_half_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_second_half_radps = Eigen::Vector3d::Zero();
  /// Largest per-axis standard deviation of the low-passed signal (0.2 s Hann means); 0 when
  /// the samples span less than 0.2 s.
  double acc_lowpass_std_mps2 = 0.0;
  double gyro_lowpass_std_radps = 0.0;
  Eigen::Vector3d gyro_lowpass_std_axes_radps = Eigen::Vector3d::Zero();  ///< per axis
  double velocity_excursion_mps = 0.0;  ///< largest per-axis |u(t) − mean u|, u = ∫(f − f̄)
  double velocity_rms_mps = 0.0;        ///< RMS of |u(t) − mean u| (all axes)
  double angle_excursion_rad = 0.0;     ///< the same for the rate
  double acc_std_mps2 = 0.0;            ///< largest per-axis standard deviation, raw (for reports)
  double gyro_std_radps = 0.0;
};

/// Over `samples` (time-ordered, at least 4). Sample spacing from their times.
ImuStillness ComputeImuStillness(std::span<const ImuSample> samples);

}  // namespace swlio::estimator

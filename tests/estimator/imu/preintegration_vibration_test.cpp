// Chassis vibration in the pre-integration (imu_noise_adapter.h): the midpoint rule's error on
// vibration the 400 Hz samples resolve is a velocity offset at each interval boundary, which
// consecutive intervals share with opposite signs; over a chain of intervals it does not add up.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "swlio/core/time.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kRateHz = 400.0;
constexpr double kGravity = 9.81;

struct Tone {
  double amplitude_mps2, frequency_hz, phase_rad;
};
/// Vertical vibration of about 2 m/s² RMS: a 23 Hz motor tone and a 67 Hz gear mesh.
constexpr std::array<Tone, 2> kTones = {{{2.0, 23.0, 0.3}, {2.0, 67.0, 1.1}}};

double VibrationMps2(double t_s) {
  double a = 0.0;
  for (const Tone& tone : kTones) {
    a += tone.amplitude_mps2 * std::sin(kTwoPi * tone.frequency_hz * t_s + tone.phase_rad);
  }
  return a;
}

/// Its exact integral from t0 to t1 (the true velocity change).
double VibrationDeltaVMps(double t0_s, double t1_s) {
  double dv = 0.0;
  for (const Tone& tone : kTones) {
    const double w = kTwoPi * tone.frequency_hz;
    dv -= tone.amplitude_mps2 / w *
          (std::cos(w * t1_s + tone.phase_rad) - std::cos(w * t0_s + tone.phase_rad));
  }
  return dv;
}

/// Noise-free samples of a robot standing still on its vibrating chassis, for `duration_s`.
std::vector<ImuSample> Samples(double duration_s) {
  std::vector<ImuSample> out;
  for (int k = 0; k <= static_cast<int>(duration_s * kRateHz); ++k) {
    const double t_s = k / kRateHz;
    ImuSample s;
    s.t_ns = SecToNs(t_s);
    s.acc_mps2 = Eigen::Vector3d(0.0, 0.0, kGravity + VibrationMps2(t_s));
    s.gyro_radps.setZero();
    out.push_back(s);
  }
  return out;
}

/// Δv_z error (measured minus true, gravity removed) of the interval [t0, t1].
double DeltaVError(const std::vector<ImuSample>& samples, int64_t t0_ns, int64_t t1_ns) {
  size_t first = 0;
  while (first + 1 < samples.size() && samples[first + 1].t_ns <= t0_ns) ++first;
  size_t last = first;
  while (last + 1 < samples.size() && samples[last].t_ns < t1_ns) ++last;
  Preintegrator pre(ImuNoiseConfig{}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const std::span<const ImuSample> span(samples.data() + first, last - first + 1);
  EXPECT_EQ(pre.Integrate(span, t0_ns, t1_ns), PreintegrationStatus::kOk);
  const double dt_s = NsToSec(t1_ns - t0_ns);
  const double measured = pre.result().delta_v.z() - kGravity * dt_s;
  return measured - VibrationDeltaVMps(NsToSec(t0_ns), NsToSec(t1_ns));
}

TEST(PreintegrationVibration, TheErrorIsABoundaryOffsetThatConsecutiveIntervalsCancel) {
  const std::vector<ImuSample> samples = Samples(7.0);
  // Sweep-like intervals of 0.1 s that start between two samples.
  const int64_t start_ns = SecToNs(0.5) + 1'234'567;
  const int64_t step_ns = SecToNs(0.1);
  constexpr int kIntervals = 50;
  double sum_sq = 0.0, chain = 0.0, max_chain = 0.0;
  for (int i = 0; i < kIntervals; ++i) {
    const double e = DeltaVError(samples, start_ns + i * step_ns, start_ns + (i + 1) * step_ns);
    sum_sq += e * e;
    chain += e;
    max_chain = std::max(max_chain, std::abs(chain));
  }
  const double rms_one = std::sqrt(sum_sq / kIntervals);
  // One interval's error is well above the MTi-G-710's white noise over 0.1 s (1.9e-4 m/s):
  // as independent noise it would have to loosen the IMU factors.
  EXPECT_GT(rms_one, 1.9e-4);
  // It is (h/12)·(Δf_start − Δf_end) (imu_noise_adapter.h): a tone of amplitude A changes by
  // A·2 sin(π f h) per sample with RMS over √2, so (h/12)·√2·σ(Δf) is the RMS to within 20 %
  // (the in-between start, the terms of order h²).
  const double h = 1.0 / kRateHz;
  double step_var = 0.0;
  for (const Tone& tone : kTones) {
    step_var +=
        std::pow(tone.amplitude_mps2 * 2.0 * std::sin(std::numbers::pi * tone.frequency_hz * h),
                 2) /
        2.0;
  }
  const double step_rms = std::sqrt(step_var);
  EXPECT_NEAR(rms_one, h / 12.0 * std::sqrt(2.0) * step_rms, 0.2 * rms_one);
  // Chained, the errors telescope: the velocity after 50 intervals is off by about what one
  // boundary contributes, not by √50 times one interval's error as white noise would be.
  EXPECT_LT(max_chain, 1.5 * rms_one);
  EXPECT_GT(std::sqrt(double{kIntervals}) * rms_one, 4.0 * max_chain);
}

}  // namespace
}  // namespace swlio::estimator

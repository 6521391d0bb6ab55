// Chassis vibration in the pre-integration: the MTi's interval means (core/types.h) integrate
// it exactly between samples; where an interval is cut between two samples the cut step takes
// the mean over its part of the sample's interval from the neighbours' line (MeanOverPart). What
// error is left is a velocity offset at the bound, which consecutive intervals share with
// opposite signs, so over a chain of intervals it does not add up. Instantaneous samples under
// the midpoint rule err more.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <span>
#include <vector>

#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_interval_means.h"
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

/// Noise-free samples of a robot standing still on its vibrating chassis, for `duration_s`:
/// instantaneous values at the stamps, or (`means`) the MTi's means over each sample interval
/// (core/types.h).
std::vector<ImuSample> Samples(double duration_s, bool means) {
  std::vector<ImuSample> out;
  const double h = 1.0 / kRateHz;
  for (int k = 0; k <= static_cast<int>(duration_s * kRateHz); ++k) {
    const double t_s = k / kRateHz;
    ImuSample s;
    s.t_ns = SecToNs(t_s);
    const double f = means && k > 0 ? VibrationDeltaVMps(t_s - h, t_s) / h : VibrationMps2(t_s);
    s.acc_mps2 = Eigen::Vector3d(0.0, 0.0, kGravity + f);
    s.gyro_radps.setZero();
    out.push_back(s);
  }
  return out;
}

/// Instantaneous samples as the estimator takes them: trapezoidal means (ImuIntervalMeans).
std::vector<ImuSample> MidpointMeans(const std::vector<ImuSample>& instants) {
  ImuIntervalMeans means;
  std::vector<ImuSample> out;
  for (const ImuSample& s : instants) out.push_back(means.Next(s));
  return out;
}

/// Δv_z error (measured minus true, gravity removed) of the interval [t0, t1], from the samples
/// the window gives it: the last before t0 to the one after the sample holding t1.
double DeltaVError(const std::vector<ImuSample>& samples, int64_t t0_ns, int64_t t1_ns) {
  size_t first = 0;
  while (first + 1 < samples.size() && samples[first + 1].t_ns <= t0_ns) ++first;
  size_t last = first;
  while (last + 1 < samples.size() && samples[last].t_ns < t1_ns) ++last;
  if (last + 1 < samples.size()) ++last;
  Preintegrator pre(ImuNoiseConfig{}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const std::span<const ImuSample> span(samples.data() + first, last - first + 1);
  EXPECT_EQ(pre.Integrate(span, t0_ns, t1_ns), PreintegrationStatus::kOk);
  const double dt_s = NsToSec(t1_ns - t0_ns);
  const double measured = pre.result().delta_v.z() - kGravity * dt_s;
  return measured - VibrationDeltaVMps(NsToSec(t0_ns), NsToSec(t1_ns));
}

struct ChainErrors {
  double rms_one = 0.0;    ///< RMS of one interval's Δv error
  double max_chain = 0.0;  ///< largest |sum| of the errors of consecutive intervals
};

/// 50 sweep-like intervals of 0.1 s from `start_ns`.
ChainErrors Chain(const std::vector<ImuSample>& samples, int64_t start_ns) {
  const int64_t step_ns = SecToNs(0.1);
  constexpr int kIntervals = 50;
  double sum_sq = 0.0, chain = 0.0;
  ChainErrors out;
  for (int i = 0; i < kIntervals; ++i) {
    const double e = DeltaVError(samples, start_ns + i * step_ns, start_ns + (i + 1) * step_ns);
    sum_sq += e * e;
    chain += e;
    out.max_chain = std::max(out.max_chain, std::abs(chain));
  }
  out.rms_one = std::sqrt(sum_sq / kIntervals);
  return out;
}

// The MTi's means integrate a vibration its output rate cannot resolve exactly between samples:
// intervals that start and end on samples have no error at all.
TEST(PreintegrationVibration, MeansIntegrateExactlyBetweenSamples) {
  const ChainErrors e = Chain(Samples(7.0, true), SecToNs(0.5));
  EXPECT_LT(e.rms_one, 1e-12);
  EXPECT_LT(e.max_chain, 1e-12);
}

// Intervals that start between two samples: each cut step takes its part's mean from the line
// through the neighbouring means, which leaves a small error at each bound, shared by
// consecutive intervals with opposite signs.
TEST(PreintegrationVibration, CutStepsErrLittleAtTheBoundsAndConsecutiveIntervalsCancel) {
  const int64_t start_ns = SecToNs(0.5) + 1'234'567;
  const ChainErrors means = Chain(Samples(7.0, true), start_ns);
  const ChainErrors midpoint = Chain(MidpointMeans(Samples(7.0, false)), start_ns);
  std::cout << "one interval's Δv error RMS: means " << means.rms_one << " m/s, midpoint rule "
            << midpoint.rms_one << " m/s; chained: " << means.max_chain << ", "
            << midpoint.max_chain << " m/s\n";
  // Chained they telescope: after 50 intervals about one bound's error, not √50 times one
  // interval's.
  for (const ChainErrors& e : {means, midpoint}) {
    EXPECT_LT(e.max_chain, 1.5 * e.rms_one);
    EXPECT_GT(std::sqrt(50.0) * e.rms_one, 4.0 * e.max_chain);
  }
  // The midpoint rule errs by several times the MTi-G-710's white noise over 0.1 s (1.9e-4
  // m/s); the MTi's means, their parts' means taken from the line, stay below it. Measured:
  // 1.4e-4 against 5.7e-4 m/s (the whole sample's value at the cuts: 6.4e-4 against 1.03e-3).
  EXPECT_GT(midpoint.rms_one, 1.9e-4);
  EXPECT_LT(means.rms_one, 1.9e-4);
  EXPECT_LT(means.rms_one, 0.4 * midpoint.rms_one);
}

// A specific force that changes linearly: the parts' means are exact, the two parts of one
// sample's interval make up its mean, and a missing neighbour or a gap leaves the whole mean.
TEST(PreintegrationVibration, MeanOverPartFollowsTheNeighboursLine) {
  const double slope_mps3 = 40.0;
  std::vector<ImuSample> s(3);
  for (int k = 0; k < 3; ++k) {
    s[k].t_ns = 2'500'000 * (k + 1);
    const double middle_s = NsToSec(s[k].t_ns) - 1.25e-3;  // the mean of a line: its middle
    s[k].acc_mps2 = Eigen::Vector3d(0.0, 0.0, slope_mps3 * middle_s);
    s[k].gyro_radps = Eigen::Vector3d(0.1 * slope_mps3 * middle_s, 0.0, 0.0);
  }
  const int64_t cut_ns = 2'500'000 + 1'700'000;  // in sample 1's interval (2.5, 5] ms
  const ImuSample before = MeanOverPart(s, 1, 2'500'000, cut_ns);
  const ImuSample after = MeanOverPart(s, 1, cut_ns, 5'000'000);
  EXPECT_EQ(before.t_ns, cut_ns);
  EXPECT_NEAR(before.acc_mps2.z(), slope_mps3 * 0.5 * (2.5e-3 + 4.2e-3), 1e-12);
  EXPECT_NEAR(after.acc_mps2.z(), slope_mps3 * 0.5 * (4.2e-3 + 5e-3), 1e-12);
  EXPECT_NEAR(before.gyro_radps.x(), 0.1 * before.acc_mps2.z(), 1e-12);
  EXPECT_NEAR(1.7 * before.acc_mps2.z() + 0.8 * after.acc_mps2.z(), 2.5 * s[1].acc_mps2.z(), 1e-12);
  // Without the sample after, or with it 5 ms on (a gap): the whole mean.
  EXPECT_EQ(MeanOverPart(std::span(s).first(2), 1, 2'500'000, cut_ns).acc_mps2, s[1].acc_mps2);
  s[2].t_ns += 2'500'000;
  EXPECT_EQ(MeanOverPart(s, 1, 2'500'000, cut_ns).acc_mps2, s[1].acc_mps2);
}

}  // namespace
}  // namespace swlio::estimator

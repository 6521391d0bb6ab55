// The online LiDAR–IMU time offset (time_offset_estimator.h): the gyro integration, the
// estimate from simulated gyro samples against noisy sweep-end attitudes (as the sweeps'
// registrations give them) for offsets of both signs, its bounded walk, the excitation gate and
// the configuration's rules.

#include "swlio/estimator/window/time_offset_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <random>

#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

TEST(TimeOffsetEstimator, IntegratesTheGyroOverAnyIntervalInsideTheSamples) {
  std::deque<ImuSample> samples;
  const Vec3 w(0.3, -0.2, 1.0);
  for (int i = 0; i <= 400; ++i) {
    ImuSample s;
    s.t_ns = i * 2'500'000;
    s.gyro_radps = w;
    samples.push_back(s);
  }
  const Vec3 bias(0.01, 0.0, -0.02);
  // An interval between samples: the rates are held exactly, the bias removed.
  const auto q = TimeOffsetEstimator::IntegrateGyro(samples, 101'234'567, 703'000'001, bias);
  ASSERT_TRUE(q.has_value());
  const Vec3 expected = (w - bias) * (0.703000001 - 0.101234567);
  EXPECT_LT((lie::QuatLog(*q) - expected).norm(), 1e-9);
  EXPECT_FALSE(TimeOffsetEstimator::IntegrateGyro(samples, -1, 100, bias).has_value());
  EXPECT_FALSE(TimeOffsetEstimator::IntegrateGyro(samples, 0, 1'000'000'001, bias).has_value());
}

struct OffsetRun {
  TimeOffsetStatus status;
  double max_step_s = 0.0;     ///< the largest change of the applied offset between sweeps
  double first_update_s = -1;  ///< drive time of the first gated estimate
  /// The largest |applied − true offset| / applied_sigma_s() over the sweeps, and the last σ.
  double max_applied_z = 0.0;
  double applied_sigma_s = 0.0;
  /// The smallest applied_sigma_s() before the first gated estimate (0: none came before it).
  double min_sigma_before_update_s = 0.0;
  /// What the window's factors follow (followed_offset_s(), followed_sigma_s()) at the end, and
  /// the largest |followed − true offset| / followed σ over the sweeps.
  double followed_s = 0.0, followed_sigma_s = 0.0, max_followed_z = 0.0;
};

/// `aggressive` seed 42 for `duration_s`, its IMU measuring the motion `offset_s` before its
/// stamps; every 0.1 s a sweep-end attitude from the truth with `sigma_rad` of noise per axis
/// (the sweeps' registrations), fed after the samples up to it, as the estimator gets them.
/// With `lean` > 0 each attitude leans that fraction toward the one the IMU gives at the offset
/// applied (the true attitude at t + lean·(applied − offset)), as a registration de-skewed and
/// started from the IMU does (measured: 0.12–0.2 on `aggressive` 42).
OffsetRun Drive(double offset_s,
                double duration_s,
                double sigma_rad,
                TimeOffsetConfig config,
                double lean = 0.0,
                double noise_correlation_s = 0.0,
                unsigned noise_seed = 3) {
  auto setup = sim::MakeSimSetup("aggressive", 42, duration_s);
  setup->imu.time_offset_s = offset_s;
  const std::vector<ImuSample> imu =
      test::ToImuSamples(sim::SimulateImu(*setup->trajectory, setup->imu, 42));
  TimeOffsetEstimator estimator(config);
  std::mt19937 rng(noise_seed);
  std::normal_distribution<double> n01;
  OffsetRun run;
  size_t next = 0;
  Vec3 noise = Vec3::Zero();
  for (int64_t t_ns = kNsPerSec; t_ns < SecToNs(duration_s) - kNsPerSec; t_ns += 100'000'000) {
    for (; next < imu.size() && imu[next].t_ns <= t_ns; ++next) estimator.AddImu(imu[next]);
    // White, or a first-order Gauss–Markov error with that correlation time (of a map region).
    const double a = noise_correlation_s > 0.0 ? std::exp(-0.1 / noise_correlation_s) : 0.0;
    const Vec3 fresh(n01(rng) * sigma_rad, n01(rng) * sigma_rad, n01(rng) * sigma_rad);
    noise = a * noise + std::sqrt(1.0 - a * a) * fresh;
    const double lean_s = lean * (estimator.status().offset_s - offset_s);
    const int64_t t_seen_ns = t_ns + static_cast<int64_t>(std::llround(lean_s * 1e9));
    const Eigen::Matrix3d R = test::TrueState(*setup->trajectory, t_seen_ns).T_world_imu.linear();
    const double before_s = estimator.status().offset_s;
    estimator.AddRegistration(t_ns, Eigen::Quaterniond(R * lie::Exp(noise)));
    run.max_step_s = std::max(run.max_step_s, std::abs(estimator.status().offset_s - before_s));
    if (run.first_update_s < 0.0 && estimator.status().updates > 0)
      run.first_update_s = NsToSec(t_ns);
    run.applied_sigma_s = estimator.applied_sigma_s();
    if (estimator.status().updates == 0 && run.applied_sigma_s > 0.0 &&
        (run.min_sigma_before_update_s == 0.0 ||
         run.applied_sigma_s < run.min_sigma_before_update_s))
      run.min_sigma_before_update_s = run.applied_sigma_s;
    if (run.applied_sigma_s > 0.0) {
      const double error_s = std::abs(estimator.status().offset_s - offset_s);
      run.max_applied_z = std::max(run.max_applied_z, error_s / run.applied_sigma_s);
    }
    run.followed_s = estimator.followed_offset_s();
    run.followed_sigma_s = estimator.followed_sigma_s();
    if (run.followed_sigma_s > 0.0) {
      const double error_s = std::abs(run.followed_s - offset_s);
      run.max_followed_z = std::max(run.max_followed_z, error_s / run.followed_sigma_s);
    }
  }
  run.status = estimator.status();
  return run;
}

class TimeOffsetDrive : public ::testing::TestWithParam<double> {};

TEST_P(TimeOffsetDrive, FoundWithinHalfAMillisecondAfterThirtySeconds) {
  const double offset_s = GetParam();
  // 0.03° of registration noise per sweep, about what a sweep's registration jitters by.
  const OffsetRun run = Drive(offset_s, 35.0, 5e-4, TimeOffsetConfig{});
  std::cout << "offset " << offset_s * 1e3 << " ms: applied " << run.status.offset_s * 1e3
            << " ms, estimate " << run.status.estimate_s * 1e3 << " ± " << run.status.sigma_s * 1e3
            << " ms, first update at " << run.first_update_s << " s, rows " << run.status.rows
            << ", excitation " << run.status.excitation_radps << " rad/s\n";
  EXPECT_NEAR(run.status.offset_s, offset_s, 5e-4);
  EXPECT_NEAR(run.status.estimate_s, offset_s, 5e-4);
  EXPECT_TRUE(run.status.gated);
  EXPECT_GT(run.status.sigma_s, 0.0);
  EXPECT_LT(run.status.sigma_s, TimeOffsetConfig{}.gate_sigma_s);
  // Walked there in bounded steps.
  EXPECT_LE(run.max_step_s, TimeOffsetConfig{}.max_step_s + 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Offsets, TimeOffsetDrive, ::testing::Values(-0.010, -0.005, 0.005, 0.010));

TEST(TimeOffsetEstimator, RegistrationsThatLeanTowardTheAppliedOffsetDoNotHoldItBack) {
  // Rows made while 10 ms were still unapplied say 8 ms; kept, they hold the estimate short.
  const double offset_s = 0.010, lean = 0.2;
  const OffsetRun run = Drive(offset_s, 32.0, 5e-4, TimeOffsetConfig{}, lean);
  TimeOffsetConfig keep_all;
  keep_all.operating_point_tolerance_s = keep_all.max_offset_s;  // rows never dropped
  const OffsetRun kept = Drive(offset_s, 32.0, 5e-4, keep_all, lean);
  std::cout << "leaning registrations, 10 ms: applied " << run.status.offset_s * 1e3
            << " ms (rows of every operating point kept: " << kept.status.offset_s * 1e3
            << " ms), rows " << run.status.rows << "\n";
  EXPECT_NEAR(run.status.offset_s, offset_s, 5e-4);
  // Measured: 0.37 ms short, 0.60 ms with every row kept.
  EXPECT_GT(std::abs(kept.status.offset_s - offset_s),
            1.5 * std::abs(run.status.offset_s - offset_s));
}

TEST(TimeOffsetEstimator, ItsSigmaCoversTheErrorWithCorrelatedRegistrationErrors) {
  // Registration errors that run together over 1 s (a turn against one part of the map): over
  // eight draws the errors must be of the size σ claims. RMS of error/σ measured 0.68; a σ half
  // as large (1.4) fails, as does one inflated until the gate could not pass (< 0.4).
  double z_sq = 0.0;
  const int draws = 8;
  for (int seed = 1; seed <= draws; ++seed) {
    const OffsetRun run =
        Drive(0.005, 35.0, 1e-3, TimeOffsetConfig{}, 0.0, 1.0, static_cast<unsigned>(seed));
    const double z = (run.status.estimate_s - 0.005) / run.status.sigma_s;
    std::cout << "draw " << seed << ": error " << (run.status.estimate_s - 0.005) * 1e3
              << " ms, sigma " << run.status.sigma_s * 1e3 << " ms\n";
    z_sq += z * z;
  }
  EXPECT_LT(std::sqrt(z_sq / draws), 1.25);
  EXPECT_GT(std::sqrt(z_sq / draws), 0.4);
}

TEST(TimeOffsetEstimator, TheAppliedSigmaCoversTheAppliedError) {
  // What the window's IMU factors are widened by when initial_sigma_s is set
  // (time_shift_jacobian.h): that σ before the first estimate, then the estimate's σ with the
  // walk still to go. 10 ms off with 5 ms initially is 2σ; the walk must not claim more
  // certainty than it has.
  TimeOffsetConfig config;
  config.initial_sigma_s = 0.005;
  for (const double offset_s : {-0.010, 0.005, 0.010}) {
    const OffsetRun run = Drive(offset_s, 35.0, 5e-4, config);
    std::cout << "offset " << offset_s * 1e3 << " ms: largest error/sigma " << run.max_applied_z
              << ", sigma at the end " << run.applied_sigma_s * 1e3 << " ms\n";
    EXPECT_LT(run.max_applied_z, 3.0);
    EXPECT_GT(run.applied_sigma_s, 0.0);
    EXPECT_LT(run.applied_sigma_s, TimeOffsetConfig{}.gate_sigma_s);
  }
  EXPECT_EQ(TimeOffsetEstimator(config).applied_sigma_s(), config.initial_sigma_s);
  // With a wide prior the rows narrow it before the gate passes where they agree with the
  // offset applied (0 here); where they see it far off it stays wide; it covers the error.
  TimeOffsetConfig wide = config;
  wide.initial_sigma_s = 0.010;
  for (const double offset_s : {-0.010, 0.0, 0.010}) {
    const OffsetRun run = Drive(offset_s, 35.0, 5e-4, wide);
    std::cout << "offset " << offset_s * 1e3 << " ms, prior 10 ms: smallest sigma before the gate "
              << run.min_sigma_before_update_s * 1e3 << " ms, first update at "
              << run.first_update_s << " s, largest error/sigma " << run.max_applied_z << "\n";
    EXPECT_GT(run.min_sigma_before_update_s, 0.0);
    if (offset_s == 0.0)
      EXPECT_LT(run.min_sigma_before_update_s, 0.1 * wide.initial_sigma_s);
    else
      EXPECT_GT(run.min_sigma_before_update_s, 0.3 * std::abs(offset_s));
    EXPECT_LT(run.max_applied_z, 3.0);
  }
  // Known, or 0: the factors stay as if the offset were known, followed or not.
  TimeOffsetConfig known = config;
  known.estimate = false;
  EXPECT_EQ(TimeOffsetEstimator(known).applied_sigma_s(), 0.0);
  EXPECT_EQ(TimeOffsetEstimator(known).followed_sigma_s(), 0.0);
  TimeOffsetConfig off = config;
  off.initial_sigma_s = 0.0;
  const OffsetRun unwidened = Drive(0.010, 35.0, 5e-4, off);
  EXPECT_EQ(unwidened.applied_sigma_s, 0.0);
  EXPECT_EQ(unwidened.followed_sigma_s, 0.0);
}

TEST(TimeOffsetEstimator, WhatTheWindowFollowsIsTheGatedEstimateWithItsSigma) {
  // window_follows_estimate: the window's IMU factors are moved to followed_offset_s() and
  // widened by followed_sigma_s(): the applied offset and applied_sigma_s() until the first
  // gated estimate, then that estimate and its σ. It must end at the truth and never claim more
  // certainty than it has.
  for (const double offset_s : {-0.010, 0.005, 0.010}) {
    const OffsetRun run = Drive(offset_s, 35.0, 5e-4, TimeOffsetConfig{});
    std::cout << "offset " << offset_s * 1e3 << " ms: followed " << run.followed_s * 1e3 << " ± "
              << run.followed_sigma_s * 1e3 << " ms, largest error/sigma " << run.max_followed_z
              << "\n";
    EXPECT_NEAR(run.followed_s, offset_s, 5e-4);
    EXPECT_GT(run.followed_sigma_s, 0.0);
    EXPECT_LT(run.followed_sigma_s, TimeOffsetConfig{}.gate_sigma_s);
    EXPECT_LT(run.max_followed_z, 3.0);
  }
  TimeOffsetConfig config;
  config.initial_offset_s = 0.004;
  const TimeOffsetEstimator fresh(config);
  EXPECT_EQ(fresh.followed_offset_s(), 0.004);
  EXPECT_EQ(fresh.followed_sigma_s(), config.initial_sigma_s);
}

TEST(TimeOffsetEstimator, WithoutRotationChangesTheGateHoldsTheOffset) {
  // The standing start of `aggressive` (the first 2 s): no change of rate, nothing to see.
  TimeOffsetConfig config;
  config.min_rows = 4;
  const OffsetRun run = Drive(0.008, 3.0, 5e-4, config);
  EXPECT_GT(run.status.rows, 4u);
  EXPECT_EQ(run.status.updates, 0u);
  EXPECT_FALSE(run.status.gated);
  EXPECT_EQ(run.status.offset_s, 0.0);
  EXPECT_GT(run.status.sigma_s, config.gate_sigma_s);
}

TEST(TimeOffsetEstimator, TheLimitBoundsTheEstimate) {
  TimeOffsetConfig config;
  config.max_offset_s = 0.004;
  const OffsetRun run = Drive(0.010, 25.0, 5e-4, config);
  EXPECT_LE(std::abs(run.status.estimate_s), 0.004 + 1e-12);
  EXPECT_LE(std::abs(run.status.offset_s), 0.004 + 1e-9);
}

TEST(TimeOffsetEstimator, DisabledItNeitherShiftsNorEstimates) {
  TimeOffsetConfig config;
  config.enabled = false;
  const OffsetRun run = Drive(0.010, 10.0, 5e-4, config);
  EXPECT_EQ(run.status.rows, 0u);
  EXPECT_EQ(run.status.offset_s, 0.0);
  EXPECT_FALSE(run.status.enabled);
  TimeOffsetEstimator e(config);
  ImuSample s;
  s.t_ns = 123;
  EXPECT_EQ(e.Shifted(s).t_ns, 123);
}

TEST(TimeOffsetEstimator, AKnownOffsetIsAppliedAndKept) {
  TimeOffsetConfig config;
  config.estimate = false;
  config.initial_offset_s = 0.007;
  const OffsetRun run = Drive(0.0, 10.0, 5e-4, config);
  EXPECT_EQ(run.status.rows, 0u);
  EXPECT_NEAR(run.status.offset_s, 0.007, 1e-12);
  TimeOffsetEstimator e(config);
  ImuSample s;
  s.t_ns = 100'000'000;
  EXPECT_EQ(e.Shifted(s).t_ns, 93'000'000);  // stamped 7 ms late
}

TEST(TimeOffsetConfig, ValidateNamesTheBadKeys) {
  EXPECT_TRUE(TimeOffsetConfig{}.Validate().empty());
  TimeOffsetConfig c;
  c.max_offset_s = -0.01;
  c.max_step_s = 0.002;  // could reorder 400 Hz samples
  c.gate_sigma_s = 0.0;
  const ConfigIssues issues = c.Validate();
  ASSERT_EQ(issues.size(), 4u);
  EXPECT_EQ(issues[0].key, "max_offset_s");
  EXPECT_EQ(issues[1].key, "initial_offset_s");  // 0 is outside [0.01, -0.01]
  EXPECT_EQ(issues[2].key, "gate_sigma_s");
  EXPECT_EQ(issues[3].key, "max_step_s");
  TimeOffsetConfig start;
  start.initial_offset_s = 0.06;  // beyond the limit
  ASSERT_EQ(start.Validate().size(), 1u);
  EXPECT_EQ(start.Validate()[0].key, "initial_offset_s");
  TimeOffsetConfig sigma;
  sigma.initial_sigma_s = -1e-3;
  ASSERT_EQ(sigma.Validate().size(), 1u);
  EXPECT_EQ(sigma.Validate()[0].key, "initial_sigma_s");
  TimeOffsetConfig window;
  window.window_prior_sigma_s = 0.06;
  ASSERT_EQ(window.Validate().size(), 1u);
  EXPECT_EQ(window.Validate()[0].key, "window_prior_sigma_s");
}

}  // namespace
}  // namespace swlio::estimator

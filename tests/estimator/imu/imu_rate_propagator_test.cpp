// ImuRatePropagator: its outputs against the closed-form level turn and against ImuPropagator
// (the same step function, so equal to the last bit), exact re-propagation after a corrected
// state, the drop counters, and no heap allocation per sample or state.

#include "swlio/estimator/imu/imu_rate_propagator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "allocation_counter.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_propagator.h"

namespace swlio::estimator {
namespace {

constexpr double kG = 9.80665;
constexpr int64_t kStepNs = 2'500'000;  // 400 Hz
constexpr double kSpeed = 1.5, kYawRate = 1.0;
const Eigen::Vector3d kBiasAcc(0.1, -0.2, 0.05), kBiasGyro(0.01, 0.0, -0.02);

// A level turn at constant speed as the IMU measures it, biases included.
ImuSample TurnSample(int64_t t_ns) {
  ImuSample s;
  s.t_ns = t_ns;
  s.gyro_radps = Eigen::Vector3d(0.0, 0.0, kYawRate) + kBiasGyro;
  s.acc_mps2 = Eigen::Vector3d(0.0, kSpeed * kYawRate, kG) + kBiasAcc;
  return s;
}

State TurnStart() {
  State s;
  s.vel_world = Eigen::Vector3d(kSpeed, 0.0, 0.0);
  s.bias_acc = kBiasAcc;
  s.bias_gyro = kBiasGyro;
  return s;
}

ImuRatePropagatorConfig Config(size_t buffer_samples = 800) {
  ImuRatePropagatorConfig config;
  config.gravity_mps2 = kG;
  config.buffer_samples = buffer_samples;
  return config;
}

void ExpectSameState(const State& a, const State& b) {
  EXPECT_EQ(a.t_ns, b.t_ns);
  EXPECT_EQ(a.T_world_imu.matrix(), b.T_world_imu.matrix());
  EXPECT_EQ(a.vel_world, b.vel_world);
  EXPECT_EQ(a.bias_acc, b.bias_acc);
  EXPECT_EQ(a.bias_gyro, b.bias_gyro);
}

TEST(ImuRatePropagator, LevelTurnEqualsImuPropagatorAndTheClosedForm) {
  ImuRatePropagator rate(Config());
  ImuPropagator reference(kG);
  ASSERT_TRUE(rate.SetState(TurnStart()).has_value());
  reference.Reset(TurnStart());
  std::optional<ImuRateOutput> out;
  for (int64_t t = 0; t <= 2 * kNsPerSec; t += kStepNs) {
    out = rate.Add(TurnSample(t));
    reference.Add(TurnSample(t));
    if (t == 0) {
      EXPECT_FALSE(out.has_value()) << "a sample at the state's time gives no new output";
      continue;
    }
    ASSERT_TRUE(out.has_value()) << t;
    ExpectSameState(out->state, reference.state());
  }
  const double t = 2.0;
  const Eigen::Vector3d expected(kSpeed / kYawRate * std::sin(kYawRate * t),
                                 kSpeed / kYawRate * (1.0 - std::cos(kYawRate * t)), 0.0);
  EXPECT_LT((out->state.T_world_imu.translation() - expected).norm(), 2e-3);
  EXPECT_NEAR(lie::RpyFromRotation(out->state.T_world_imu.linear()).z(), kYawRate * t, 1e-9);
  EXPECT_NEAR(out->state.vel_world.norm(), kSpeed, 1e-3);
  EXPECT_LT((out->gyro_imu_radps - Eigen::Vector3d(0.0, 0.0, kYawRate)).norm(), 1e-15);
  EXPECT_EQ(out->since_optimized_ns, 2 * kNsPerSec);
}

TEST(ImuRatePropagator, ANewStateRepropagatesTheBufferedSamplesExactly) {
  ImuRatePropagator rate(Config());
  rate.SetState(TurnStart());
  for (int64_t t = 0; t <= 800 * kNsPerMs; t += kStepNs) rate.Add(TurnSample(t));
  const uint64_t repropagated_before = rate.counters().repropagated;

  // The optimizer's answer for t_k = 0.5 s + 1.25 ms (between two samples), arriving at 0.8 s.
  State corrected = TurnStart();
  corrected.t_ns = 500 * kNsPerMs + kStepNs / 2;
  corrected.T_world_imu.translation() = Eigen::Vector3d(0.45, 0.2, 0.03);
  corrected.T_world_imu.linear() = lie::Exp(Eigen::Vector3d(0.01, -0.02, 0.49));
  corrected.vel_world = Eigen::Vector3d(1.3, 0.7, 0.01);
  corrected.bias_acc = kBiasAcc + Eigen::Vector3d(0.02, 0.0, -0.01);
  corrected.bias_gyro = kBiasGyro + Eigen::Vector3d(0.0, 0.001, 0.002);
  const std::optional<ImuRateOutput> out = rate.SetState(corrected);

  // Integrating from the corrected state through the same samples (the one at 0.5 s is the
  // trapezoid's left end of the first interval).
  ImuPropagator reference(kG);
  reference.Add(TurnSample(500 * kNsPerMs));
  reference.Reset(corrected);
  for (int64_t t = 500 * kNsPerMs + kStepNs; t <= 800 * kNsPerMs; t += kStepNs) {
    reference.Add(TurnSample(t));
  }
  ASSERT_TRUE(out.has_value());
  ExpectSameState(out->state, reference.state());
  EXPECT_EQ(out->since_optimized_ns, 800 * kNsPerMs - corrected.t_ns);
  EXPECT_EQ(rate.counters().repropagated - repropagated_before, 120u);  // (0.5, 0.8] s
  EXPECT_EQ(rate.buffered(), 121u);
  for (int64_t t = 800 * kNsPerMs + kStepNs; t <= kNsPerSec; t += kStepNs) {
    const std::optional<ImuRateOutput> next = rate.Add(TurnSample(t));
    reference.Add(TurnSample(t));
    ASSERT_TRUE(next.has_value());
    ExpectSameState(next->state, reference.state());
  }
  ImuPropagator uncorrected(kG);
  uncorrected.Reset(TurnStart());
  for (int64_t t = 0; t <= kNsPerSec; t += kStepNs) uncorrected.Add(TurnSample(t));
  EXPECT_GT(
      (reference.state().T_world_imu.translation() - uncorrected.state().T_world_imu.translation())
          .norm(),
      0.01)
      << "the correction must show in the output";
}

// With a re-basing rate, a new state does not make the output jump: the output keeps its pose
// at the re-basing and takes the correction in at the rate (each step the motion plus at most
// rate × period), reaching the re-propagated state once the correction is used up; a
// correction over rebase_max_m is taken at once.
TEST(ImuRatePropagator, ReBasingTakesACorrectionInAtItsRateWithoutAJump) {
  ImuRatePropagatorConfig config = Config();
  config.rebase_rate_mps = 0.1;
  config.rebase_rate_radps = 0.05;
  ImuRatePropagator smooth(config), plain(Config());
  smooth.SetState(TurnStart());
  plain.SetState(TurnStart());
  Eigen::Isometry3d last = Eigen::Isometry3d::Identity();
  for (int64_t t = 0; t <= 500 * kNsPerMs; t += kStepNs) {
    last = smooth.Add(TurnSample(t))->state.T_world_imu;
    plain.Add(TurnSample(t));
  }
  // A correction of 8 mm and 0.2° at 0.4 s (what an optimized state moves the output by).
  State corrected = TurnStart();
  ImuPropagator reference(kG);
  reference.Reset(TurnStart());
  for (int64_t t = 0; t <= 400 * kNsPerMs; t += kStepNs) reference.Add(TurnSample(t));
  corrected = reference.state();
  corrected.T_world_imu.translation() += Eigen::Vector3d(0.006, -0.005, 0.002);
  corrected.T_world_imu.linear() =
      corrected.T_world_imu.linear() * lie::Exp(Eigen::Vector3d(0.0, 0.0, 0.0035));
  const Eigen::Isometry3d at_rebase = smooth.SetState(corrected)->state.T_world_imu;
  const Eigen::Isometry3d target = plain.SetState(corrected)->state.T_world_imu;
  EXPECT_LT((at_rebase.translation() - last.translation()).norm(), 1e-12) << "no jump";
  EXPECT_GT((target.translation() - last.translation()).norm(), 0.007) << "the plain one jumps";
  // Every later step: the motion of one period (≤ 1.5 m/s · 2.5 ms) plus ≤ 0.1 m/s · 2.5 ms.
  const double max_step_m = kSpeed * 2.5e-3 + 0.1 * 2.5e-3 + 1e-9;
  Eigen::Isometry3d previous = at_rebase;
  for (int64_t t = 500 * kNsPerMs + kStepNs; t <= 700 * kNsPerMs; t += kStepNs) {
    const Eigen::Isometry3d now = smooth.Add(TurnSample(t))->state.T_world_imu;
    const Eigen::Isometry3d exact = plain.Add(TurnSample(t))->state.T_world_imu;
    EXPECT_LE((now.translation() - previous.translation()).norm(), max_step_m) << t;
    previous = now;
    if (t >= 600 * kNsPerMs) {  // 8 mm at 0.1 m/s: used up after 80 ms
      EXPECT_LT((now.translation() - exact.translation()).norm(), 1e-6) << t;
      EXPECT_LT(lie::Angle(now.linear().transpose() * exact.linear()), 1e-6) << t;
    }
  }
  // A re-initialization's 0.5 m: at once.
  State far = corrected;
  far.T_world_imu.translation() += Eigen::Vector3d(0.5, 0.0, 0.0);
  const Eigen::Isometry3d jumped = smooth.SetState(far)->state.T_world_imu;
  EXPECT_TRUE(jumped.isApprox(plain.SetState(far)->state.T_world_imu, 1e-12));
}

TEST(ImuRatePropagator, SamplesBeforeTheFirstStateAreBufferedThenIntegrated) {
  ImuRatePropagator rate(Config());
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(rate.Add(TurnSample(i * kStepNs)).has_value());
  EXPECT_EQ(rate.counters().before_state, 10u);
  State start = TurnStart();
  start.t_ns = 3 * kStepNs;
  const std::optional<ImuRateOutput> out = rate.SetState(start);

  ImuPropagator reference(kG);
  reference.Add(TurnSample(3 * kStepNs));
  reference.Reset(start);
  for (int i = 4; i < 10; ++i) reference.Add(TurnSample(i * kStepNs));
  ASSERT_TRUE(out.has_value());
  ExpectSameState(out->state, reference.state());
  EXPECT_EQ(rate.buffered(), 7u) << "samples before the state's time are dropped but one";
}

TEST(ImuRatePropagator, OutOfOrderAndDuplicateSamplesAreDroppedAndCounted) {
  ImuRatePropagator clean(Config()), noisy(Config());
  clean.SetState(TurnStart());
  noisy.SetState(TurnStart());
  std::optional<ImuRateOutput> a, b;
  for (int i = 1; i <= 20; ++i) {
    a = clean.Add(TurnSample(i * kStepNs));
    b = noisy.Add(TurnSample(i * kStepNs));
    if (i % 5 == 0) {
      EXPECT_FALSE(noisy.Add(TurnSample(i * kStepNs)).has_value());        // duplicate
      EXPECT_FALSE(noisy.Add(TurnSample((i - 2) * kStepNs)).has_value());  // late
    }
  }
  EXPECT_EQ(noisy.counters().out_of_order, 8u);
  EXPECT_EQ(noisy.counters().samples, 20u);
  ASSERT_TRUE(a.has_value() && b.has_value());
  ExpectSameState(a->state, b->state);
}

TEST(ImuRatePropagator, AFullBufferDropsTheOldestAndCountsIt) {
  ImuRatePropagator rate(Config(4));
  for (int i = 1; i <= 10; ++i) rate.Add(TurnSample(i * kStepNs));
  EXPECT_EQ(rate.counters().overflow_dropped, 6u);
  EXPECT_EQ(rate.buffered(), 4u);
  const std::optional<ImuRateOutput> out = rate.SetState(TurnStart());  // older than the buffer
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->state.t_ns, 10 * kStepNs);
  EXPECT_EQ(rate.counters().repropagated, 4u);
}

TEST(ImuRatePropagator, AStateOlderThanThePreviousIsRejected) {
  ImuRatePropagator rate(Config());
  State newer = TurnStart();
  newer.t_ns = 10 * kStepNs;
  ASSERT_TRUE(rate.SetState(newer).has_value());
  EXPECT_FALSE(rate.SetState(TurnStart()).has_value());
  EXPECT_EQ(rate.counters().stale_states, 1u);
  EXPECT_EQ(rate.counters().states, 1u);
  EXPECT_FALSE(rate.Add(TurnSample(9 * kStepNs)).has_value()) << "older than the state";
  const std::optional<ImuRateOutput> out = rate.Add(TurnSample(11 * kStepNs));
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->since_optimized_ns, kStepNs);
}

TEST(ImuRatePropagator, ClearForgetsTheStateAndTheSamples) {
  ImuRatePropagator rate(Config());
  State newer = TurnStart();
  newer.t_ns = 10 * kStepNs;
  rate.SetState(newer);
  for (int i = 11; i <= 20; ++i) ASSERT_TRUE(rate.Add(TurnSample(i * kStepNs)).has_value());
  rate.Clear();
  EXPECT_FALSE(rate.has_state());
  EXPECT_EQ(rate.buffered(), 0u);
  EXPECT_FALSE(rate.Add(TurnSample(kStepNs)).has_value()) << "no state: buffered only";
  EXPECT_EQ(rate.counters().out_of_order, 0u) << "an earlier time is accepted after Clear";
  ASSERT_TRUE(rate.SetState(TurnStart()).has_value()) << "an older state is accepted too";
  EXPECT_EQ(rate.counters().stale_states, 0u);
}

TEST(ImuRatePropagator, NoHeapAllocationPerSampleOrState) {
  ImuRatePropagator rate(Config(100));
  rate.SetState(TurnStart());
  const int64_t before = test::HeapAllocations();
  int outputs = 0;
  for (int i = 1; i <= 1000; ++i) {  // fills the ring several times over between states
    if (rate.Add(TurnSample(i * kStepNs)).has_value()) ++outputs;
    if (i % 300 == 0) {
      State s = TurnStart();
      s.t_ns = (i - 20) * kStepNs;
      if (rate.SetState(s).has_value()) ++outputs;
    }
  }
  EXPECT_EQ(test::HeapAllocations() - before, 0);
  EXPECT_EQ(outputs, 1003);
  EXPECT_GT(rate.counters().overflow_dropped, 0u);
}

TEST(ImuRatePropagatorConfig, ValidateNamesTheBadKeys) {
  EXPECT_TRUE(Config().Validate().empty());
  ImuRatePropagatorConfig config = Config(1);
  config.gravity_mps2 = 0.0;
  const ConfigIssues issues = config.Validate();
  ASSERT_EQ(issues.size(), 2u);
  EXPECT_EQ(issues[0].key, "gravity_mps2");
  EXPECT_EQ(issues[1].key, "buffer_samples");
}

}  // namespace
}  // namespace swlio::estimator

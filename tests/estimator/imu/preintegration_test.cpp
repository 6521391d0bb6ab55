// Pre-integration against the simulator's true motion, direct integration, its own noise
// model and central differences.

#include "swlio/estimator/imu/preintegration.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <iostream>

#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/imu/imu_residual.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

constexpr double kG = 9.80665;

struct SimData {
  std::optional<sim::SimSetup> setup;
  std::vector<sim::SimImuSample> sim;
  std::vector<ImuSample> imu;
};

SimData MakeData(const char* scenario, uint64_t seed, double duration_s, bool noise_free) {
  SimData d;
  d.setup = sim::MakeSimSetup(scenario, seed, duration_s);
  if (noise_free) test::MakeNoiseFree(*d.setup);
  d.sim = sim::SimulateImu(*d.setup->trajectory, d.setup->imu, seed);
  d.imu = test::ToImuSamples(d.sim);
  return d;
}

/// Index of the last simulated sample at or before t_ns (for the true bias).
size_t SampleAt(const std::vector<sim::SimImuSample>& sim, int64_t t_ns) {
  size_t k = 0;
  while (k + 1 < sim.size() && sim[k + 1].t_true_ns <= t_ns) ++k;
  return k;
}

TEST(Preintegration, NoiseFreeMatchesTrueMotion) {
  const SimData d = MakeData("aggressive", 3, 30.0, true);
  ImuNoiseConfig noise;
  double max_rot = 0.0, max_vel = 0.0, max_pos = 0.0;
  for (double t0 = 2.0013; t0 < 28.0; t0 += 0.77) {
    for (const double len : {0.1, 1.0}) {
      const int64_t t_i = SecToNs(t0), t_j = SecToNs(t0 + len);
      Preintegrator pre(noise, Vec3::Zero(), Vec3::Zero());
      ASSERT_EQ(pre.Integrate(d.imu, t_i, t_j), PreintegrationStatus::kOk);
      EXPECT_NEAR(pre.result().dt_s, len, 1e-9);
      const State truth_i = test::TrueState(*d.setup->trajectory, t_i);
      const State truth_j = test::TrueState(*d.setup->trajectory, t_j);
      const State pred = PredictState(truth_i, pre.result(), GravityWorld(kG));
      EXPECT_EQ(pred.t_ns, t_j);
      const Mat3 dR = pred.T_world_imu.linear().transpose() * truth_j.T_world_imu.linear();
      max_rot = std::max(max_rot, lie::Log(dR).norm());
      max_vel = std::max(max_vel, (pred.vel_world - truth_j.vel_world).norm());
      max_pos = std::max(
          max_pos, (pred.T_world_imu.translation() - truth_j.T_world_imu.translation()).norm());
    }
  }
  std::cout << "noise-free max error over 1 s: rot " << max_rot << " rad, vel " << max_vel
            << " m/s, pos " << max_pos << " m\n";
  // The cut steps at both bounds take their sample's whole mean: about ω̇·h²/8 each, with
  // ω̇ ~ 1 rad/s² and h = 2.5 ms 1e-6 rad.
  EXPECT_LT(max_rot, 4e-6);
  EXPECT_LT(max_vel, 2e-5);
  EXPECT_LT(max_pos, 1e-5);
}

// Direct integration in the world frame, sample by sample, with the same scheme (each step
// takes its later sample's interval means) and biases: pre-integration + PredictState must give
// the same end state to rounding.
TEST(Preintegration, MatchesDirectWorldFrameIntegration) {
  const SimData d = MakeData("aggressive", 2, 12.0, false);
  const Vec3 bg(0.002, -0.001, 0.003), ba(0.05, -0.03, 0.02);
  const Vec3 g = GravityWorld(kG);
  State start = test::TrueState(*d.setup->trajectory, SecToNs(5.0));
  start.bias_gyro = bg;
  start.bias_acc = ba;
  const size_t k0 = SampleAt(d.sim, SecToNs(5.0)), k1 = k0 + 400;
  start.t_ns = d.imu[k0].t_ns;
  Mat3 R = start.T_world_imu.linear();
  Vec3 p = start.T_world_imu.translation(), v = start.vel_world;
  for (size_t k = k0; k < k1; ++k) {
    const double dt = NsToSec(d.imu[k + 1].t_ns - d.imu[k].t_ns);
    const Vec3 theta = (d.imu[k + 1].gyro_radps - bg) * dt;
    const Vec3 a = d.imu[k + 1].acc_mps2 - ba;
    const Vec3 a_world = R * lie::Exp(0.5 * theta) * a + g;
    p += v * dt + 0.5 * a_world * dt * dt;
    v += a_world * dt;
    R = R * lie::Exp(theta);
  }
  Preintegrator pre(ImuNoiseConfig{}, bg, ba);
  ASSERT_EQ(pre.Integrate(d.imu, d.imu[k0].t_ns, d.imu[k1].t_ns), PreintegrationStatus::kOk);
  const State end = PredictState(start, pre.result(), g);
  EXPECT_LT(lie::Log(end.T_world_imu.linear().transpose() * R).norm(), 1e-10);
  EXPECT_LT((end.vel_world - v).norm(), 1e-9);
  EXPECT_LT((end.T_world_imu.translation() - p).norm(), 1e-9);
}

// With noise, the residual at the true states and true biases is a sample of the propagated
// covariance: normalized squared error ≈ χ²(9) on average, and ≥ 97 % of the components
// within 3σ.
TEST(Preintegration, CovarianceIsConsistentWithSimulatedNoise) {
  const SimData d = MakeData("aggressive", 1, 60.0, false);
  const ImuNoiseConfig noise;  // the same MTi-G-710 densities as the simulator
  ASSERT_NEAR(noise.acc_noise_density_mps2_per_sqrthz, d.setup->imu.noise.acc_noise_density, 1e-12);
  ASSERT_NEAR(noise.gyro_noise_density_radps_per_sqrthz, d.setup->imu.noise.gyro_noise_density,
              1e-12);
  double nees_sum = 0.0;
  int within = 0, components = 0, intervals = 0;
  for (double t0 = 2.5; t0 + 1.0 < 58.0; t0 += 0.5) {
    const int64_t t_i = SecToNs(t0), t_j = SecToNs(t0 + 0.5);
    const sim::SimImuSample& truth_bias = d.sim[SampleAt(d.sim, t_i)];
    Preintegrator pre(noise, truth_bias.bias_gyro, truth_bias.bias_acc);
    ASSERT_EQ(pre.Integrate(d.imu, t_i, t_j), PreintegrationStatus::kOk);
    const Vec9 r = ImuResidual(pre.result(), ToNavPoint(test::TrueState(*d.setup->trajectory, t_i)),
                               ToNavPoint(test::TrueState(*d.setup->trajectory, t_j)),
                               truth_bias.bias_gyro, truth_bias.bias_acc, GravityWorld(kG));
    const Mat9& cov = pre.result().covariance;
    nees_sum += r.dot(cov.ldlt().solve(r));
    for (int c = 0; c < 9; ++c) {
      within += std::abs(r[c]) <= 3.0 * std::sqrt(cov(c, c)) ? 1 : 0;
      ++components;
    }
    ++intervals;
  }
  const double mean_nees = nees_sum / intervals;
  const double frac = static_cast<double>(within) / components;
  std::cout << intervals << " intervals: mean NEES " << mean_nees << " (χ²(9) mean 9), "
            << 100.0 * frac << " % of components within 3σ\n";
  ASSERT_GE(intervals, 100);
  EXPECT_GT(mean_nees, 9.0 * 0.75);
  EXPECT_LT(mean_nees, 9.0 * 1.3);
  EXPECT_GE(frac, 0.97);
}

// Streaming steps give exactly what Integrate() gives on sample-aligned bounds, and the kept
// samples re-integrate with new biases like a fresh integration.
TEST(Preintegration, StreamingStepsAndReintegration) {
  const SimData d = MakeData("short", 1, 8.0, false);
  const Vec3 bg(1e-3, 0.0, -2e-3), ba(0.01, 0.02, 0.0);
  const size_t k0 = 1200, k1 = 1240;
  Preintegrator streamed(ImuNoiseConfig{}, bg, ba);
  streamed.Reset(d.imu[k0].t_ns, bg, ba);
  for (size_t k = k0; k < k1; ++k) streamed.IntegrateStep(d.imu[k], d.imu[k + 1]);
  Preintegrator batch(ImuNoiseConfig{}, bg, ba);
  ASSERT_EQ(batch.Integrate(d.imu, d.imu[k0].t_ns, d.imu[k1].t_ns), PreintegrationStatus::kOk);
  EXPECT_EQ(streamed.result().t_end_ns, d.imu[k1].t_ns);
  EXPECT_LT((streamed.result().delta_p - batch.result().delta_p).norm(), 1e-15);
  EXPECT_LT((streamed.result().covariance - batch.result().covariance).norm(), 1e-20);

  const Vec3 bg2 = bg + Vec3(0.02, -0.01, 0.0);
  streamed.Reintegrate(bg2, ba);
  Preintegrator fresh(ImuNoiseConfig{}, bg2, ba);
  ASSERT_EQ(fresh.Integrate(d.imu, d.imu[k0].t_ns, d.imu[k1].t_ns), PreintegrationStatus::kOk);
  EXPECT_LT((streamed.result().delta_v - fresh.result().delta_v).norm(), 1e-15);
  EXPECT_LT((streamed.result().jacobian_bias - fresh.result().jacobian_bias).norm(), 1e-12);
  EXPECT_GT((streamed.result().delta_v - batch.result().delta_v).norm(), 1e-4);  // it changed
}

TEST(Preintegration, ReportsUncoveredAndBadIntervals) {
  std::vector<ImuSample> s(3);
  s[0].t_ns = 100;
  s[1].t_ns = 200;
  s[2].t_ns = 300;
  Preintegrator pre(ImuNoiseConfig{}, Vec3::Zero(), Vec3::Zero());
  EXPECT_EQ(pre.Integrate(s, 50, 250), PreintegrationStatus::kNotCovered);
  EXPECT_EQ(pre.Integrate(s, 150, 350), PreintegrationStatus::kNotCovered);
  EXPECT_EQ(pre.Integrate(s, 250, 150), PreintegrationStatus::kBadInterval);
  EXPECT_EQ(pre.Integrate({}, 150, 250), PreintegrationStatus::kNotCovered);
  EXPECT_EQ(pre.Integrate(s, 150, 250), PreintegrationStatus::kOk);
  EXPECT_NEAR(pre.result().dt_s, 100e-9, 1e-18);
  EXPECT_EQ(pre.Integrate(s, 200, 200), PreintegrationStatus::kOk);
  EXPECT_EQ(pre.result().dt_s, 0.0);
  std::swap(s[0], s[1]);
  EXPECT_EQ(pre.Integrate(s, 150, 250), PreintegrationStatus::kUnsortedTime);
}

// An IMU gap can leave one sample before a sweep's interval and the next after it: the
// interval is then one interpolated step. White acceleration noise integrated over that step
// gives Cov(δp) = σ_a² Δt³/3, Cov(δp, δv) = σ_a² Δt²/2, Cov(δv) = σ_a² Δt: full rank, so the
// interval still gets an IMU factor. (With Δp's noise at σ_a² Δt³/4, as the sample-averaged
// discrete noise alone gives, δp and δv were perfectly correlated, Σ singular and
// ImuFactor::Create refused the interval: the sweep's velocity and biases were left free.)
TEST(Preintegration, OneStepAcrossAnImuGapHasAFullRankCovariance) {
  std::vector<ImuSample> s(2);  // zero rate and specific force: no attitude coupling
  s[0].t_ns = 0;
  s[1].t_ns = 200'000'000;  // 200 ms without samples
  const ImuNoiseConfig noise;
  Preintegrator pre(noise, Vec3::Zero(), Vec3::Zero());
  ASSERT_EQ(pre.Integrate(s, 50'000'000, 150'000'000), PreintegrationStatus::kOk);
  const double dt = 0.1;
  const double q =
      noise.acc_noise_density_mps2_per_sqrthz * noise.acc_noise_density_mps2_per_sqrthz;
  const Eigen::Matrix<double, 9, 9>& cov = pre.result().covariance;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(cov(kRowP + i, kRowP + i), q * dt * dt * dt / 3.0, 1e-9 * q) << "δp, axis " << i;
    EXPECT_NEAR(cov(kRowP + i, kRowV + i), q * dt * dt / 2.0, 1e-9 * q) << "δp δv, axis " << i;
    EXPECT_NEAR(cov(kRowV + i, kRowV + i), q * dt, 1e-9 * q) << "δv, axis " << i;
  }
  using Llt = Eigen::LLT<Eigen::Matrix<double, 9, 9>>;
  EXPECT_EQ(Llt(cov).info(), Eigen::Success);
  EXPECT_NE(ImuFactor::Create(pre.result(), noise, kG), nullptr);
}

// Bounds: the samples hold the means of ω_z = 0.2 + t and a_z = 1 + 2t over their 10 ms
// intervals; the window starts and ends mid-interval, where the cut steps take the mean over
// their part of the interval from the neighbours' line (MeanOverPart). For linear functions that
// is exact: ΔR and Δv match their integrals to rounding, Δp the scheme's steps with those means.
TEST(Preintegration, CutStepsAtTheBoundsTakeTheirPartsMeans) {
  constexpr double h = 0.01;
  const auto rate = [](double t) { return 0.2 + t; };
  const auto force = [](double t) { return 1.0 + 2.0 * t; };
  std::vector<ImuSample> s;
  for (int k = 0; k < 20; ++k) {  // a linear function's mean is its value at the middle
    ImuSample x;
    x.t_ns = k * 10'000'000LL;
    x.gyro_radps = Vec3(0.0, 0.0, rate((k - 0.5) * h));
    x.acc_mps2 = Vec3(0.0, 0.0, force((k - 0.5) * h));
    s.push_back(x);
  }
  Preintegrator pre(ImuNoiseConfig{}, Vec3::Zero(), Vec3::Zero());
  const double t0 = 0.013, t1 = 0.157, T = t1 - t0;
  ASSERT_EQ(pre.Integrate(s, SecToNs(t0), SecToNs(t1)), PreintegrationStatus::kOk);
  EXPECT_NEAR(pre.result().dt_s, T, 1e-12);
  double angle = 0.0, v = 0.0, p = 0.0;
  for (double a = t0; a < t1 - 1e-12;) {  // the pieces between t0, the sample times, t1
    const double b = std::min(t1, std::floor(a / h + 1e-9) * h + h);
    const double middle = 0.5 * (a + b);  // the mean of a linear function over [a, b]
    angle += rate(middle) * (b - a);
    p += v * (b - a) + 0.5 * force(middle) * (b - a) * (b - a);
    v += force(middle) * (b - a);
    a = b;
  }
  EXPECT_LT((lie::Log(pre.result().delta_R) - Vec3(0, 0, angle)).norm(), 1e-12);
  EXPECT_NEAR(pre.result().delta_v.z(), v, 1e-12);
  EXPECT_NEAR(pre.result().delta_p.z(), p, 1e-12);
  EXPECT_NEAR(v, T + (t1 * t1 - t0 * t0), 1e-12);
  EXPECT_NEAR(angle, 0.2 * T + 0.5 * (t1 * t1 - t0 * t0), 1e-12);
}

}  // namespace
}  // namespace swlio::estimator

// Cost of IMU pre-integration: per integrated sample (mean, covariance and bias Jacobians),
// per first-order bias correction, per re-integration, per residual with Jacobians.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "swlio/estimator/imu/imu_residual.h"
#include "swlio/estimator/imu/preintegration.h"

namespace {

using swlio::ImuSample;
using swlio::estimator::Preintegrator;
using Vec3 = Eigen::Vector3d;

/// 400 Hz samples of a body turning and accelerating (synthetic, deterministic).
std::vector<ImuSample> MakeSamples(int n) {
  std::vector<ImuSample> out(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double t = k * 0.0025;
    ImuSample& s = out[static_cast<size_t>(k)];
    s.t_ns = static_cast<int64_t>(k) * 2'500'000;
    s.gyro_radps = Vec3(0.1 * std::sin(t), 0.05 * std::cos(2 * t), 0.5 * std::sin(0.5 * t));
    s.acc_mps2 = Vec3(0.3 * std::cos(t), 0.2 * std::sin(3 * t), 9.81 + 0.1 * std::sin(t));
  }
  return out;
}

const Vec3 kBg(0.001, -0.002, 0.0005);
const Vec3 kBa(0.02, 0.01, -0.03);

// One interval of 40 samples (a 10 Hz LiDAR scan at 400 Hz), bounds interpolated.
void BM_IntegratePerSample(benchmark::State& state) {
  const std::vector<ImuSample> samples = MakeSamples(42);
  Preintegrator pre(swlio::estimator::ImuNoiseConfig{}, kBg, kBa);
  const int64_t t0 = 1'000'000, t1 = 101'000'000;  // 40 steps
  for (auto _ : state) {
    pre.Integrate(samples, t0, t1);
    benchmark::DoNotOptimize(pre.result().delta_p);
  }
  state.SetItemsProcessed(state.iterations() * 40);
}
BENCHMARK(BM_IntegratePerSample);

// Streaming step only (no bounds handling, no sample copy).
void BM_IntegrateStep(benchmark::State& state) {
  const std::vector<ImuSample> samples = MakeSamples(401);
  Preintegrator pre(swlio::estimator::ImuNoiseConfig{}, kBg, kBa);
  size_t k = 0;
  for (auto _ : state) {
    if (k + 1 >= samples.size()) {
      pre.Reset(samples[0].t_ns, kBg, kBa);
      k = 0;
    }
    pre.IntegrateStep(samples[k], samples[k + 1]);
    ++k;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IntegrateStep);

void BM_BiasCorrection(benchmark::State& state) {
  const std::vector<ImuSample> samples = MakeSamples(42);
  Preintegrator pre(swlio::estimator::ImuNoiseConfig{}, kBg, kBa);
  pre.Integrate(samples, 1'000'000, 101'000'000);
  const Vec3 bg = kBg + Vec3(1e-4, 2e-4, -1e-4), ba = kBa + Vec3(0.01, 0.0, 0.005);
  for (auto _ : state) {
    benchmark::DoNotOptimize(swlio::estimator::Corrected(pre.result(), bg, ba));
  }
}
BENCHMARK(BM_BiasCorrection);

void BM_Reintegrate40(benchmark::State& state) {
  const std::vector<ImuSample> samples = MakeSamples(42);
  Preintegrator pre(swlio::estimator::ImuNoiseConfig{}, kBg, kBa);
  pre.Integrate(samples, 1'000'000, 101'000'000);
  for (auto _ : state) {
    pre.Reintegrate(kBg + Vec3(0.02, 0.0, 0.0), kBa);
    benchmark::DoNotOptimize(pre.result().delta_p);
  }
}
BENCHMARK(BM_Reintegrate40);

void BM_ResidualWithJacobians(benchmark::State& state) {
  const std::vector<ImuSample> samples = MakeSamples(42);
  Preintegrator pre(swlio::estimator::ImuNoiseConfig{}, kBg, kBa);
  pre.Integrate(samples, 1'000'000, 101'000'000);
  swlio::estimator::NavPoint si, sj;
  sj.R_world_imu = Eigen::AngleAxisd(0.05, Vec3::UnitZ()).toRotationMatrix();
  sj.p_world = Vec3(0.1, 0.0, 0.0);
  sj.v_world = Vec3(1.0, 0.0, 0.0);
  swlio::estimator::ImuResidualJacobians J;
  const Vec3 g = swlio::estimator::GravityWorld(9.80665);
  for (auto _ : state) {
    benchmark::DoNotOptimize(swlio::estimator::ImuResidual(pre.result(), si, sj, kBg, kBa, g, &J));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ResidualWithJacobians);

}  // namespace

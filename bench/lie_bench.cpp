// Cost of the SO(3) primitives used in every IMU step and residual.
#include <benchmark/benchmark.h>

#include "swlio/core/lie.h"

namespace {

const swlio::lie::Vec3 kPhi(0.3, -0.2, 0.5);

void BM_Exp(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(swlio::lie::Exp(kPhi));
}
BENCHMARK(BM_Exp);

void BM_Log(benchmark::State& state) {
  const swlio::lie::Mat3 R = swlio::lie::Exp(kPhi);
  for (auto _ : state) benchmark::DoNotOptimize(swlio::lie::Log(R));
}
BENCHMARK(BM_Log);

void BM_RightJacobianInverse(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(swlio::lie::RightJacobianInverse(kPhi));
}
BENCHMARK(BM_RightJacobianInverse);

}  // namespace

// Cost of the window optimization's building blocks: one Evaluate (residual + all Jacobians)
// of each factor, and one marginalization of a frame with N point-to-plane residuals, its IMU
// factor, an earlier prior and the extrinsic kept (synthetic, deterministic data).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "swlio/core/lie.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/registration/point_to_line_factor.h"
#include "swlio/estimator/registration/point_to_plane_factor.h"
#include "swlio/estimator/window/marginalization.h"

namespace {

namespace est = swlio::estimator;
using Vec3 = Eigen::Vector3d;
using Block = std::vector<double>;

// 0.1 s of 400 Hz samples of a turning, accelerating body.
est::PreintegratedImu MakePreintegration() {
  std::vector<swlio::ImuSample> samples(42);
  for (size_t k = 0; k < samples.size(); ++k) {
    const double t = static_cast<double>(k) * 0.0025;
    samples[k].t_ns = static_cast<int64_t>(k) * 2'500'000;
    samples[k].gyro_radps = Vec3(0.1 * std::sin(t), 0.05, 0.5 * std::cos(t));
    samples[k].acc_mps2 = Vec3(0.3, 0.2 * std::sin(3 * t), 9.81);
  }
  est::Preintegrator pre(est::ImuNoiseConfig{}, Vec3::Zero(), Vec3::Zero());
  pre.Integrate(samples, 1'000'000, 101'000'000);
  return pre.result();
}

Block Pose(const Vec3& p, const Vec3& phi) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = swlio::lie::Exp(phi);
  T.translation() = p;
  Block x(est::kPoseSize);
  est::PoseToParameters(T, x.data());
  return x;
}

struct Frames {
  Block pose_i = Pose({1, 2, 0.5}, {0.01, -0.02, 0.3});
  Block pose_j = Pose({1.1, 2.05, 0.5}, {0.01, -0.02, 0.35});
  Block sb_i = Block(est::kSpeedBiasSize, 0.01);
  Block sb_j = Block(est::kSpeedBiasSize, 0.01);
  Block extrinsic = Pose({0.1, 0, 0.2}, {0, 0, 1.57});
};

template <int kResiduals, int kBlocks>
void EvaluateLoop(benchmark::State& state,
                  const ceres::CostFunction& f,
                  const std::vector<const double*>& params,
                  const std::vector<int>& sizes) {
  double r[kResiduals];
  std::vector<std::vector<double>> J(kBlocks);
  double* jp[kBlocks];
  for (int k = 0; k < kBlocks; ++k) {
    J[static_cast<size_t>(k)].resize(
        static_cast<size_t>(kResiduals * sizes[static_cast<size_t>(k)]));
    jp[k] = J[static_cast<size_t>(k)].data();
  }
  for (auto _ : state) {
    f.Evaluate(params.data(), r, jp);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(jp[0]);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_ImuFactorEvaluate(benchmark::State& state) {
  const auto f = est::ImuFactor::Create(MakePreintegration(), est::ImuNoiseConfig{}, 9.80665);
  Frames fr;
  EvaluateLoop<15, 4>(state, *f,
                      {fr.pose_i.data(), fr.sb_i.data(), fr.pose_j.data(), fr.sb_j.data()},
                      {7, 9, 7, 9});
}
BENCHMARK(BM_ImuFactorEvaluate);

void BM_PointToPlaneEvaluate(benchmark::State& state) {
  const auto f = est::PointToPlaneFactor::Create({5, -2, 1}, {0.2, 0.1, 1}, {3, 0, 0}, 50.0);
  Frames fr;
  EvaluateLoop<1, 2>(state, *f, {fr.pose_i.data(), fr.extrinsic.data()}, {7, 7});
}
BENCHMARK(BM_PointToPlaneEvaluate);

void BM_PointToLineEvaluate(benchmark::State& state) {
  const auto f = est::PointToLineFactor::Create({5, -2, 1}, {0, 0, 1}, {3, 0, 0}, 50.0);
  Frames fr;
  EvaluateLoop<2, 2>(state, *f, {fr.pose_i.data(), fr.extrinsic.data()}, {7, 7});
}
BENCHMARK(BM_PointToLineEvaluate);

// Marginalizing frame i: N planes on pose_i (+ extrinsic, kept), the IMU factor i→j, and the
// previous prior over frame i (a dense 15-row prior built once, outside the timing).
void BM_MarginalizeFrame(benchmark::State& state) {
  const int planes = static_cast<int>(state.range(0));
  Frames fr;
  est::PoseManifold manifold;
  std::mt19937 rng(1);
  std::normal_distribution<double> n01;
  std::vector<std::unique_ptr<est::PointToPlaneFactor>> lidar;
  for (int k = 0; k < planes; ++k) {
    const Vec3 n(n01(rng), n01(rng), n01(rng));
    lidar.push_back(est::PointToPlaneFactor::Create(Vec3(n01(rng), n01(rng), n01(rng)) * 10.0, n,
                                                    Vec3(n01(rng), n01(rng), n01(rng)), 50.0));
  }
  const auto imu = est::ImuFactor::Create(MakePreintegration(), est::ImuNoiseConfig{}, 9.80665);
  // An earlier prior on frame i: marginalize a copy of the same frame once.
  Block pose_h = fr.pose_i, sb_h = fr.sb_i;
  est::Marginalizer first;
  first.AddParameterBlock(pose_h.data(), 7, &manifold, est::BlockRole::kMarginalize);
  first.AddParameterBlock(sb_h.data(), 9, nullptr, est::BlockRole::kMarginalize);
  first.AddParameterBlock(fr.pose_i.data(), 7, &manifold, est::BlockRole::kKeep);
  first.AddParameterBlock(fr.sb_i.data(), 9, nullptr, est::BlockRole::kKeep);
  first.AddResidualBlock(imu.get(), nullptr,
                         {pose_h.data(), sb_h.data(), fr.pose_i.data(), fr.sb_i.data()});
  const est::MarginalizationResult old = first.Marginalize();

  for (auto _ : state) {
    est::Marginalizer m;
    m.AddParameterBlock(fr.pose_i.data(), 7, &manifold, est::BlockRole::kMarginalize);
    m.AddParameterBlock(fr.sb_i.data(), 9, nullptr, est::BlockRole::kMarginalize);
    m.AddParameterBlock(fr.pose_j.data(), 7, &manifold, est::BlockRole::kKeep);
    m.AddParameterBlock(fr.sb_j.data(), 9, nullptr, est::BlockRole::kKeep);
    m.AddParameterBlock(fr.extrinsic.data(), 7, &manifold, est::BlockRole::kKeep);
    for (const auto& f : lidar)
      m.AddResidualBlock(f.get(), nullptr, {fr.pose_i.data(), fr.extrinsic.data()});
    m.AddResidualBlock(imu.get(), nullptr,
                       {fr.pose_i.data(), fr.sb_i.data(), fr.pose_j.data(), fr.sb_j.data()});
    if (old.prior != nullptr) m.AddResidualBlock(old.prior.get(), nullptr, old.kept_blocks);
    const est::MarginalizationResult result = m.Marginalize();
    benchmark::DoNotOptimize(result.rank);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MarginalizeFrame)->Arg(300)->Arg(1000)->Arg(3000)->Unit(benchmark::kMillisecond);

}  // namespace

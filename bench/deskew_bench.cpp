// De-skew of one simulated RS16 sweep (deskew.h) against a 400 Hz IMU pose track.
// Input: the `aggressive` scenario, seed 1, the sweep from 9.3 s (1.5 m/s, in a slalom turn
// at 57 °/s). The simulator's labelled sweep is already perfectly de-skewed; it is
// "re-skewed" here with the true pose at each point's own time, so the bench sees what the
// decoder delivers, and the de-skewed result can be checked against the truth (counters).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"
#include "swlio/core/time.h"
#include "swlio/estimator/frontend/deskew.h"

namespace {

using namespace swlio::estimator;  // NOLINT(google-build-using-namespace): bench file only

constexpr int64_t kImuPeriodNs = 2'500'000;  // 400 Hz

struct DeskewInput {
  swlio::Scan raw;                     ///< points in the LiDAR frame at their own time
  std::vector<Eigen::Vector3d> truth;  ///< the same points in the LiDAR frame at t_end
  PoseTrack track;                     ///< true T_world_imu at 400 Hz around the sweep
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  double yaw_rate_dps = 0.0;  ///< at the sweep's middle
  double speed_mps = 0.0;
};

Eigen::Isometry3d TrueImuPose(const swlio::sim::SimSetup& setup, int64_t t_ns) {
  const swlio::sim::Kinematics k = setup.trajectory->At(swlio::NsToSec(t_ns));
  Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
  T_world_imu.linear() = k.R_world_body;
  T_world_imu.translation() = k.p_world;
  return T_world_imu;
}

DeskewInput MakeInput() {
  auto setup = swlio::sim::MakeSimSetup("aggressive", 1, 10.0);
  if (!setup) std::abort();
  swlio::sim::LabelledScanSource source(*setup);
  swlio::sim::LabelledScan ls;
  if (!source.Next(&ls, 9.3)) std::abort();
  DeskewInput in;
  in.T_imu_lidar = setup->lidar.T_imu_lidar;
  in.raw = ls.scan;
  const Eigen::Isometry3d& T_world_lidar_end = ls.T_world_lidar_end;
  for (auto& p : in.raw.points) {
    const Eigen::Vector3d p_end = p.xyz_m.cast<double>();
    in.truth.push_back(p_end);
    const Eigen::Isometry3d T_world_lidar_i =
        TrueImuPose(*setup, in.raw.t_start_ns + p.dt_ns) * in.T_imu_lidar;
    p.xyz_m = (T_world_lidar_i.inverse() * (T_world_lidar_end * p_end)).cast<float>();
  }
  // IMU samples on a 2.5 ms grid that brackets the sweep.
  const int64_t t0 = (in.raw.t_start_ns / kImuPeriodNs - 1) * kImuPeriodNs;
  for (int64_t t = t0; t <= in.raw.t_end_ns + kImuPeriodNs; t += kImuPeriodNs) {
    in.track.Add(t, TrueImuPose(*setup, t));
  }
  const swlio::sim::Kinematics mid =
      setup->trajectory->At(swlio::NsToSec((in.raw.t_start_ns + in.raw.t_end_ns) / 2));
  in.yaw_rate_dps = mid.omega_body.z() * 180.0 / std::numbers::pi;
  in.speed_mps = mid.v_world.norm();
  return in;
}

const DeskewInput& Input() {
  static const DeskewInput in = MakeInput();
  return in;
}

void BM_Deskew(benchmark::State& state) {
  const DeskewInput& in = Input();
  std::vector<Eigen::Vector3d> out;
  DeskewResult r;
  for (auto _ : state) {
    r = Deskew(in.raw, in.track, in.T_imu_lidar, &out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.raw.points.size()));
  double max_err_m = 0.0;
  double max_skew_m = 0.0;
  for (size_t i = 0; i < out.size(); ++i) {
    max_err_m = std::max(max_err_m, (out[i] - in.truth[i]).norm());
    max_skew_m = std::max(max_skew_m, (in.raw.points[i].xyz_m.cast<double>() - in.truth[i]).norm());
  }
  state.counters["points"] = static_cast<double>(r.points);
  state.counters["uncovered"] = static_cast<double>(r.uncovered);
  state.counters["max_err_mm"] = max_err_m * 1e3;  // de-skewed vs true
  state.counters["max_skew_m"] = max_skew_m;       // raw vs true: what de-skew removes
  state.counters["yaw_rate_dps"] = in.yaw_rate_dps;
  state.counters["speed_mps"] = in.speed_mps;
}
BENCHMARK(BM_Deskew)->Unit(benchmark::kMicrosecond);

// One interpolated pose (binary search over the 40-odd samples, slerp, lerp).
void BM_PoseTrackAt(benchmark::State& state) {
  const DeskewInput& in = Input();
  Eigen::Isometry3d T;
  const int64_t span = in.raw.t_end_ns - in.raw.t_start_ns;
  int64_t t = 0;
  for (auto _ : state) {
    t = (t + 7'919'113) % span;  // pseudo-random times across the sweep
    benchmark::DoNotOptimize(in.track.At(in.raw.t_start_ns + t, &T));
    benchmark::DoNotOptimize(T.data());
  }
}
BENCHMARK(BM_PoseTrackAt);

// Filling the track: 42 poses (what the propagator hands over per sweep) + the de-skew.
void BM_TrackAndDeskew(benchmark::State& state) {
  const DeskewInput& in = Input();
  std::vector<std::pair<int64_t, Eigen::Isometry3d>> poses;
  Eigen::Isometry3d T;
  const int64_t t0 = (in.raw.t_start_ns / kImuPeriodNs - 1) * kImuPeriodNs;
  for (int64_t t = t0; t <= in.raw.t_end_ns + kImuPeriodNs; t += kImuPeriodNs) {
    if (!in.track.At(t, &T)) std::abort();
    poses.emplace_back(t, T);
  }
  PoseTrack track;
  std::vector<Eigen::Vector3d> out;
  for (auto _ : state) {
    track.Clear();
    for (const auto& [t, pose] : poses) track.Add(t, pose);
    Deskew(in.raw, track, in.T_imu_lidar, &out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.raw.points.size()));
  state.counters["poses"] = static_cast<double>(poses.size());
}
BENCHMARK(BM_TrackAndDeskew)->Unit(benchmark::kMicrosecond);

}  // namespace

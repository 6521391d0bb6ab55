#pragma once
/// @file
/// Helpers of imu_rate_latency_bench: a recording folder to replay (the simulator's `short`
/// drive written to a temporary folder when none is given), its IMU samples, its rig extrinsic
/// and its ground truth. Setup only: nothing here runs while the bench measures.

#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/types.h"
#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/recording/recording_reader.h"

namespace swlio::bench {

/// Writes the simulator's `short` drive (seed 1) into a new temporary folder, as
/// `swlio-sim --scenario short --seed 1 --out DIR` would. Empty path on failure.
inline std::filesystem::path WriteShortDrive(std::string* error) {
  const auto setup = sim::MakeSimSetup("short", 1);
  if (!setup) {
    *error = "no `short` scenario";
    return {};
  }
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("swlio_latency_bench_" + std::to_string(getpid()));
  sim::RecordingStats stats;
  if (!sim::WriteRecording(*setup, dir, &stats, error)) return {};
  return dir;
}

/// Every IMU sample of the recording, through the daemon's decoders and clock model (one pass
/// of RecordingReader, which also assembles the sweeps; they are dropped here).
inline bool ReadImu(const std::filesystem::path& dir,
                    const daemon::DaemonConfig& config,
                    std::vector<ImuSample>* imu,
                    std::string* error) {
  auto reader = daemon::RecordingReader::Open(dir, config.lidar, config.imu, error);
  if (!reader) return false;
  daemon::RecordingEvent e;
  while (reader->Next(&e)) {
    if (e.kind == daemon::RecordingEvent::Kind::kImu) imu->push_back(e.imu);
  }
  return !imu->empty();
}

/// Ground truth of a simulator recording (groundtruth.tum: IMU frame in the world, host time).
struct Truth {
  std::vector<int64_t> t_ns;
  std::vector<Eigen::Isometry3d> T_world_imu;

  bool Load(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      double t_s = 0, p[3], q[4];
      if (std::sscanf(line.c_str(), "%lf %lf %lf %lf %lf %lf %lf %lf", &t_s, &p[0], &p[1], &p[2],
                      &q[0], &q[1], &q[2], &q[3]) != 8) {
        continue;
      }
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
      T.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
      t_ns.push_back(static_cast<int64_t>(std::llround(t_s * 1e9)));
      T_world_imu.push_back(T);
    }
    return t_ns.size() >= 2;
  }

  /// The pose at `t`, interpolated (position linear, attitude slerp); nullopt outside.
  std::optional<Eigen::Isometry3d> At(int64_t t) const {
    if (t_ns.size() < 2 || t < t_ns.front() || t > t_ns.back()) return std::nullopt;
    const auto hi =
        static_cast<size_t>(std::upper_bound(t_ns.begin(), t_ns.end(), t) - t_ns.begin());
    const size_t i = hi == t_ns.size() ? hi - 2 : hi - 1;
    const double a = static_cast<double>(t - t_ns[i]) / static_cast<double>(t_ns[i + 1] - t_ns[i]);
    const Eigen::Quaterniond q0(T_world_imu[i].linear()), q1(T_world_imu[i + 1].linear());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q0.slerp(a, q1).toRotationMatrix();
    T.translation() =
        (1.0 - a) * T_world_imu[i].translation() + a * T_world_imu[i + 1].translation();
    return T;
  }
};

}  // namespace swlio::bench

// swlio-run: runs the estimator offline on a recording folder (simulator output or a daemon
// recording) through the same decoders and clock models as the daemon, and writes the IMU-frame
// trajectory in TUM format (stamped at each sweep's end, host time).

#include <CLI/CLI.hpp>

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "swlio/core/lie.h"
#include "swlio/daemon/recording_reader.h"
#include "swlio/estimator/lidar_odometry.h"

namespace {

/// T_imu_lidar from a simulator manifest (translation_m and quaternion_xyzw lines), if present.
bool ExtrinsicFromManifest(const std::string& dir, Eigen::Isometry3d* T) {
  std::ifstream in(dir + "/manifest.yaml");
  std::string line;
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1};
  int found = 0;
  while (std::getline(in, line)) {
    if (std::sscanf(line.c_str(), " translation_m: [%lf, %lf, %lf]", &t[0], &t[1], &t[2]) == 3) {
      ++found;
    }
    if (std::sscanf(line.c_str(), " quaternion_xyzw: [%lf, %lf, %lf, %lf]", &q[0], &q[1], &q[2],
                    &q[3]) == 4) {
      ++found;
    }
  }
  if (found != 2) return false;
  T->setIdentity();
  T->linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
  T->translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  return true;
}

/// Stage timings use this thread's CPU time: on a shared machine it is the time the work took
/// on one core, unaffected by other load (on an idle core it equals the wall time).
int64_t ThreadCpuNs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

void WriteTum(std::ostream& out, const swlio::State& state) {
  const Eigen::Quaterniond q = swlio::lie::PositiveW(Eigen::Quaterniond(state.T_world_imu.linear()));
  const Eigen::Vector3d p = state.T_world_imu.translation();
  char line[256];
  std::snprintf(line, sizeof line, "%lld.%09lld %.6f %.6f %.6f %.9f %.9f %.9f %.9f",
                static_cast<long long>(state.t_ns / 1'000'000'000),
                static_cast<long long>(state.t_ns % 1'000'000'000), p.x(), p.y(), p.z(), q.x(),
                q.y(), q.z(), q.w());
  out << line << '\n';
}

void WriteTimings(std::ostream& out, const swlio::estimator::OdometryResult& r, int64_t t_ns) {
  char line[256];
  std::snprintf(line, sizeof line, "%lld,%zu,%.4f,%.4f,%.4f,%.4f", static_cast<long long>(t_ns),
                r.points_in, r.times.frontend_ms, r.times.match_ms, r.times.optimize_ms,
                r.times.total_ms);
  out << line << '\n';
}

int Run(int argc, char** argv) {
  CLI::App app{"swlio-run: the estimator offline on a recording folder"};
  std::string dir, out, mode = "lidar-only";
  app.add_option("dir", dir, "recording folder (lidar.pcap, imu.xbus, imu.rx.csv)")->required();
  app.add_option("--mode", mode, "lidar-only")->check(CLI::IsMember({"lidar-only"}));
  app.add_option("--out", out, "trajectory (TUM)")->required();
  std::string timings_path;
  app.add_option("--timings", timings_path,
                 "per-scan stage timings CSV (t_ns,points,frontend_ms,match_ms,optimize_ms,total_ms), thread CPU time");
  CLI11_PARSE(app, argc, argv);

  swlio::estimator::LidarOdometryConfig config;
  if (!ExtrinsicFromManifest(dir, &config.T_imu_lidar)) {
    std::cerr << "swlio-run: no extrinsic in " << dir << "/manifest.yaml; using identity\n";
  }
  std::string error;
  auto reader = swlio::daemon::RecordingReader::Open(dir, swlio::drivers::LidarConfig{},
                                                     swlio::drivers::ImuConfig{}, &error);
  if (!reader) {
    std::cerr << "swlio-run: " << error << "\n";
    return 1;
  }
  swlio::estimator::LidarOdometry odometry(config, &ThreadCpuNs);
  std::ofstream tum(out);
  std::ofstream timings;
  if (!timings_path.empty()) {
    timings.open(timings_path);
    timings << "t_ns,points,frontend_ms,match_ms,optimize_ms,total_ms\n";
  }
  tum << "# timestamp tx ty tz qx qy qz qw  (IMU frame, host time, sweep end)\n";
  swlio::daemon::RecordingEvent e;
  size_t scans = 0, tracked = 0, failed = 0;
  double total_ms = 0.0, planes = 0.0, edges = 0.0, iterations = 0.0, inliers = 0.0;
  while (reader->Next(&e)) {
    if (e.kind == swlio::daemon::RecordingEvent::Kind::kImu) {
      odometry.AddImu(e.imu);
      continue;
    }
    const auto r = odometry.AddScan(e.scan);
    ++scans;
    total_ms += r.times.total_ms;
    if (timings.is_open()) WriteTimings(timings, r, e.scan.t_end_ns);
    if (r.status == swlio::estimator::OdometryStatus::kInitializing) continue;
    (r.status == swlio::estimator::OdometryStatus::kTracking ? tracked : failed)++;
    planes += static_cast<double>(r.planes);
    edges += static_cast<double>(r.edges);
    iterations += r.match.iterations;
    inliers += static_cast<double>(r.match.plane_inliers + r.match.edge_inliers);
    WriteTum(tum, r.state);
  }
  const double used = std::max<double>(1.0, static_cast<double>(tracked + failed));
  std::printf(
      "{\"scans\": %zu, \"tracked\": %zu, \"match_failed\": %zu, \"mean_scan_ms\": %.2f, "
      "\"mean_planes\": %.0f, \"mean_edges\": %.0f, \"mean_inliers\": %.0f, "
      "\"mean_iterations\": %.2f}\n",
      scans, tracked, failed, total_ms / used, planes / used, edges / used, inliers / used,
      iterations / used);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "swlio-run: " << e.what() << "\n";
    return 2;
  }
}

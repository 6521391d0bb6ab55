// The daemon's threads end to end: the simulator streams a drive live (UDP to 127.0.0.1, Xbus on
// a pseudo-terminal) into a Runtime, which publishes over DDS (loopback XML) to a subscriber.

#include "swlio/daemon/runtime/runtime.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "live_drive.h"
#include "swlio/daemon/recording/recording_reader.h"
#include "swlio/ipc/point_cloud.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using test::kSanitized;

TEST(Runtime, TracksASimulatedDriveAndPublishesOverDds) {
  test::LiveDrive drive;
  drive.record_dir = ::swlio::test::MakeTempDir("runtime") / "recording";
  // With loop closure: its thread takes the window's keyframes (no place is seen twice on this
  // drive, so no loop) and the health reports it.
  // GNSS too (the simulated MTi-G-710 sends GnssPvtData at 4 Hz over the pty): the fixes go
  // imu_rx → propagator → loop closure; 9 m are enough to align with a 5 m span.
  drive.adjust_config = [](DaemonConfig* c) {
    c->loop_closure.enabled = true;
    c->loop_closure.gnss.enabled = true;
    c->loop_closure.gnss.align_min_distance_m = 5.0;
  };
  const test::LiveDriveResult r = test::RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  const HealthSnapshot& s = r.final;
  EXPECT_TRUE(s.loop_closure.enabled);
  // ~9 m driven: ~45 keyframes at the window's 0.2 m spacing, ~8 nodes at 1 m, in Release; under
  // ASan (0.5x, sweeps skipped while behind) a CI run saw 16 and 4.
  EXPECT_GE(s.loop_closure.keyframes, 10u);
  EXPECT_GE(s.loop_closure.nodes, 3u);
  if (!kSanitized) {
    EXPECT_GE(s.loop_closure.keyframes, 30u);
    EXPECT_GE(s.loop_closure.nodes, 6u);
  }
  EXPECT_EQ(s.loop_closure.accepted, 0u);
  // ~11 s of fixes at 4 Hz after the first at 1 s; one per second is used.
  EXPECT_TRUE(s.loop_closure.gnss);
  EXPECT_GE(s.propagator.gnss_fixes, 30u);
  EXPECT_EQ(s.propagator.gnss_unusable, 0u);
  EXPECT_EQ(s.loop_closure.gnss_fixes, s.propagator.gnss_fixes);
  if (!kSanitized) {
    EXPECT_TRUE(s.loop_closure.gnss_aligned);
    EXPECT_GE(s.loop_closure.gnss_edges, 3u);
  }
  bool loop_status = false;
  for (const auto& h : r.published_health)
    for (const auto& st : h.msg.status)
      loop_status = loop_status || st.name == "swlio: loop closure";
  EXPECT_TRUE(loop_status) << "the health over DDS has the loop-closure status";
  EXPECT_TRUE(r.ready) << "READY condition: sensors stream and the estimator has a state";
  // Under a sanitizer the estimator may run behind and skip sweeps (SweepShedding); in the
  // Release build it keeps up.
  EXPECT_GE(s.optimizer.processed + s.optimizer.skipped_behind, 90u);
  if (!kSanitized) {
    EXPECT_EQ(s.optimizer.skipped_behind, 0u);
  }
  EXPECT_GT(s.optimizer.map_points, 1000u) << "the local maps hold the keyframes' features";
  EXPECT_NE(s.optimizer.tracking, TrackingState::kLost);
  EXPECT_NE(s.optimizer.tracking, TrackingState::kInitializing);
  EXPECT_GE(r.poses.size(), 1000u) << "IMU-rate poses received over DDS";
  // One odometry per processed sweep; under a sanitizer the sweeps skipped while behind have
  // none (a TSan CI run: 66 published).
  EXPECT_GE(r.odometry + (kSanitized ? s.optimizer.skipped_behind : 0u), 70u);
  EXPECT_GE(r.published_health.size(), 5u);
  EXPECT_EQ(s.optimizer.lidar.bad_packets, 0u);
  // The current sweep for viewers (best effort, every tracked sweep): in map, every point of a
  // RoboSense sweep (~16,000 of 28,800).
  EXPECT_TRUE(s.sweeps.enabled);
  EXPECT_GE(s.sweeps.published, 60u);
  EXPECT_EQ(s.sweeps.failures, 0u);
  ASSERT_GE(r.sweeps.size(), 10u) << "sweeps received over DDS (best effort, reader depth 1)";
  const ipc::PointCloud2& sweep = r.sweeps.back().msg;
  EXPECT_EQ(sweep.frame_id, "map");
  EXPECT_GT(sweep.width, 5000u);
  ASSERT_TRUE(ipc::HasXyzLayout(sweep));
  double max_range_m = 0.0;
  for (size_t i = 0; i < sweep.width; i += 97) {
    const auto p = ipc::XyzAt(sweep, i);
    max_range_m = std::max(max_range_m, std::hypot(double(p[0]), double(p[1])));
  }
  EXPECT_GT(max_range_m, 5.0) << "the points are spread around the sensor, not collapsed";
  // The recording holds every datagram and serial byte the rx threads received, and reads
  // back through the replay path.
  std::string read_error;
  auto reader =
      RecordingReader::Open(drive.record_dir, WithManifestPorts(drive.record_dir, r.config.lidar),
                            r.config.imu, &read_error);
  ASSERT_NE(reader, nullptr) << read_error;
  RecordingEvent e;
  size_t scans = 0;
  while (reader->Next(&e)) scans += e.kind == RecordingEvent::Kind::kScan ? 1 : 0;
  EXPECT_EQ(reader->stats().lidar_packets, s.optimizer.lidar.data_packets);
  EXPECT_EQ(reader->stats().imu_samples, s.propagator.samples);
  EXPECT_GE(scans, s.optimizer.processed);
  EXPECT_NEAR(ManifestExtrinsic(drive.record_dir)->translation().x(),
              r.setup->lidar.T_imu_lidar.translation().x(), 1e-8);
  // Lossless whenever the simulator delivered everything. On a loaded machine it can fall
  // behind and then write more than the pty holds (it drops and counts those bytes, as a UART
  // would): the daemon must then report them, not hide them.
  const bool fed_everything = r.stats.imu_bytes_dropped == 0 && r.stats.udp_errors == 0;
  if (fed_everything) {
    EXPECT_EQ(ImuChecksumErrors(s), 0u);
    EXPECT_EQ(s.propagator.decode.missing_packets, 0u);
    if (!kSanitized && r.stats.max_lateness_ms < 50.0) {
      EXPECT_EQ(TotalDrops(s), 0u) << HealthReporter().StatusLine(s);
    }
  } else {
    std::cout << "[ note ] the simulator fell behind (" << r.stats.max_lateness_ms << " ms, "
              << r.stats.imu_bytes_dropped
              << " IMU bytes dropped); daemon: " << HealthReporter().StatusLine(s) << "\n";
    EXPECT_GT(s.propagator.decode.missing_packets + ImuChecksumErrors(s) + ImuSkippedBytes(s) +
                  s.optimizer.lidar.missing_packets,
              0u)
        << "what the simulator dropped shows in the health";
  }
}

/// clock_offsets.csv's offsets (realtime − monotonic), in order.
std::vector<int64_t> RecordedOffsets(const std::filesystem::path& dir) {
  std::ifstream in(dir / "clock_offsets.csv");
  std::string line;
  std::getline(in, line);  // header
  std::vector<int64_t> out;
  while (std::getline(in, line)) out.push_back(std::stoll(line.substr(line.find(',') + 1)));
  return out;
}

// Issue 34: a +10 s step of the wall clock mid-drive (injected: time namespaces do not
// virtualize CLOCK_REALTIME). The published stamps (ROS time, the default) jump by 10 s once;
// the daemon's own time, the sensor clock models and the estimate do not notice; the health
// reports the step and the recording keeps both clocks.
TEST(Runtime, AWallClockStepMovesTheStampsOnly) {
  constexpr int64_t kStepNs = 10'000'000'000;
  constexpr double kStepAtSimS = 6.5;
  // Host time of the step: fixed once the simulator starts streaming (its preparation takes
  // seconds under a sanitizer: a step timed from the test's start came before the drive).
  std::atomic<int64_t> step_at_ns{std::numeric_limits<int64_t>::max()};
  test::LiveDrive drive;
  drive.dds_domain = 157;
  drive.record_dir = ::swlio::test::MakeTempDir("wall-clock-step") / "recording";
  drive.adjust_config = [](DaemonConfig* c) { c->ipc.stamp_clock = "realtime"; };
  drive.on_sim_start = [&step_at_ns](int64_t start_ns, double speed) {
    step_at_ns = start_ns + static_cast<int64_t>(kStepAtSimS / speed * 1e9);
  };
  drive.stamp_clocks.realtime = [&step_at_ns] {
    return RealtimeNowNs() + (MonotonicNowNs() >= step_at_ns.load() ? kStepNs : 0);
  };
  const test::LiveDriveResult r = test::RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  ASSERT_NEAR(r.SimTime(step_at_ns.load()), kStepAtSimS, 1e-6);
  // Health: one step of +10 s, published as a warning.
  EXPECT_EQ(r.final.stamp_clock.steps, 1u);
  EXPECT_NEAR(static_cast<double>(r.final.stamp_clock.last_step_ns), 1e10, 1e5);
  // The step as measured: the injected source reads the two clocks one after the other, so a
  // slow (TSan) build sees a few microseconds less than 10 s (+9.999988 s once).
  const std::string kStepSaid = "wall clock stepped by ";
  const std::string* said = r.LastPublished("swlio: time", kStepSaid);
  ASSERT_NE(said, nullptr) << "the health topic reports the step";
  EXPECT_NEAR(std::stod(said->substr(said->find(kStepSaid) + kStepSaid.size())), 10.0, 1e-3);
  // Stamps: ROS time (the subscriber's CLOCK_REALTIME, within the pose's age), then 10 s ahead.
  ASSERT_GE(r.poses.size(), 1000u);
  size_t before = 0, after = 0, jumps = 0, host_time_jumps = 0, position_jumps = 0;
  int64_t previous_host_ns = 0;
  Eigen::Vector3d previous_p = Eigen::Vector3d::Zero();
  std::vector<std::pair<double, Eigen::Vector3d>> track;  // (simulation time, position)
  for (size_t i = 0; i < r.poses.size(); ++i) {
    const auto& p = r.poses[i];
    const int64_t lead_ns = p.msg.t_ns - p.receive_realtime_ns;  // −age, or +10 s − age
    const bool stepped = lead_ns > kStepNs / 2;
    ASSERT_LT(std::llabs(lead_ns - (stepped ? kStepNs : 0)), 2'000'000'000) << "pose " << i;
    (stepped ? after : before) += 1;
    // Back on the daemon's clock: the stamp minus the offset it was given.
    const int64_t host_ns =
        p.msg.t_ns - (p.receive_realtime_ns - p.receive_steady_ns) - (stepped ? kStepNs : 0);
    const Eigen::Vector3d position(p.msg.pose.position_m.data());
    if (i > 0) {
      jumps += std::llabs(p.msg.t_ns - r.poses[i - 1].msg.t_ns - kStepNs) < 500'000'000 ? 1 : 0;
      const int64_t dt_ns = host_ns - previous_host_ns;
      host_time_jumps += dt_ns < -1'000'000 || dt_ns > 500'000'000 ? 1 : 0;
      position_jumps += (position - previous_p).norm() > 0.2 ? 1 : 0;
    }
    previous_host_ns = host_ns;
    previous_p = position;
    track.emplace_back(r.SimTime(host_ns), position);
  }
  EXPECT_GE(before, 400u);
  EXPECT_GE(after, 400u);
  EXPECT_EQ(jumps, 1u) << "the stamps jump once, by 10 s";
  EXPECT_EQ(host_time_jumps, 0u) << "on the daemon's clock the poses neither go back nor jump";
  EXPECT_EQ(position_jumps, 0u) << "the estimate is continuous";
  // The distance driven across the step, estimated (poses placed by their stamps taken back to
  // the daemon's clock) as the truth has it.
  auto estimated = [&track](double t_s) {
    auto best = track.front();
    for (const auto& e : track)
      best = std::abs(e.first - t_s) < std::abs(best.first - t_s) ? e : best;
    EXPECT_NEAR(best.first, t_s, 0.05) << "a pose near " << t_s << " s";
    return best.second;
  };
  const double t_step_s = kStepAtSimS;
  const double t0_s = std::max(t_step_s - 2.0, 3.0), t1_s = t_step_s + 2.0;
  const double driven_m =
      (r.setup->trajectory->At(t1_s).p_world - r.setup->trajectory->At(t0_s).p_world).norm();
  EXPECT_GT(driven_m, 1.0) << "the step comes while driving";
  // Only when the simulator kept its schedule: sent seconds late, its samples' receive times are
  // not its simulation times (a loaded machine: 1.5 s late, 0.65 and 1.0 m off; 0.13 and 0.27 s
  // late, 1.5 cm).
  const double estimated_m = (estimated(t1_s) - estimated(t0_s)).norm();
  std::cout << "[ note ] driven across the step: " << estimated_m << " m estimated, " << driven_m
            << " m true\n";
  if (!test::kSanitized && r.stats.max_lateness_ms < 200.0) {
    EXPECT_NEAR(estimated_m, driven_m, 0.05)
        << "driven from " << t0_s << " to " << t1_s << " s of simulation time";
  }
  // The estimator and the sensor clock models run on CLOCK_MONOTONIC: nothing happened.
  const HealthSnapshot& s = r.final;
  EXPECT_NE(s.optimizer.tracking, TrackingState::kLost);
  EXPECT_NE(s.optimizer.tracking, TrackingState::kInitializing);
  EXPECT_EQ(s.optimizer.reinitializations, 0u);
  if (r.stats.max_lateness_ms < 200.0) {  // a sender seconds behind looks like a clock step
    EXPECT_EQ(s.optimizer.lidar_clock.jumps, 0u);
    EXPECT_EQ(s.propagator.clock_jumps, 0u);
  }
  // The recording relates the clocks: the offset at the start, then 10 s more.
  const std::vector<int64_t> offsets = RecordedOffsets(drive.record_dir);
  ASSERT_GE(offsets.size(), 2u);
  EXPECT_NEAR(static_cast<double>(offsets.back() - offsets.front()), 1e10, 1e6);
  std::ifstream manifest(drive.record_dir / "manifest.yaml");
  std::stringstream text;
  text << manifest.rdbuf();
  EXPECT_NE(text.str().find("stamp_clock: realtime\n"), std::string::npos);
  EXPECT_NE(text.str().find("\nrealtime_minus_monotonic_ns: " + std::to_string(offsets.front())),
            std::string::npos);
}

}  // namespace
}  // namespace swlio::daemon

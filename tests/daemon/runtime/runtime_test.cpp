// The daemon's threads end to end: the simulator streams a drive live (UDP to 127.0.0.1, Xbus on
// a pseudo-terminal) into a Runtime, which publishes over DDS (loopback XML) to a subscriber.

#include "swlio/daemon/runtime/runtime.h"

#include <gtest/gtest.h>

#include <iostream>

#include "live_drive.h"
#include "swlio/daemon/recording/recording_reader.h"
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

}  // namespace
}  // namespace swlio::daemon

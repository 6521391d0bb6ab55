// The daemon's threads end to end: the simulator streams a drive live (UDP to 127.0.0.1, Xbus on
// a pseudo-terminal) into a Runtime, which publishes over DDS (loopback XML) to a subscriber.

#include "swlio/daemon/runtime.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <iostream>
#include <thread>

#include "sim_live.h"
#include "sim_setup.h"
#include "swlio/daemon/recording_reader.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/subscriber.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;  // several times slower: the optimizer may fall behind
#else
constexpr bool kSanitized = false;
#endif

TEST(Runtime, TracksASimulatedDriveAndPublishesOverDds) {
  const auto setup = sim::MakeSimSetup("short", 11, 12.0);
  ASSERT_TRUE(setup.has_value());
  const auto dir = test::MakeTempDir("runtime");
  DaemonConfig config;
  config.lidar.bind_address = "127.0.0.1";
  config.lidar.msop_port = 0;  // any free port; told to the simulator below
  config.lidar.difop_port = 0;
  config.imu.device = (dir / "imu.pty").string();
  config.imu.configure_on_start = false;
  config.ipc.domain_id = 117;
  config.ipc.dds_config_file = (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string();
  RuntimeOptions options;
  options.T_imu_lidar = setup->lidar.T_imu_lidar;
  const double speed = kSanitized ? 0.5 : 1.0;
  options.time_scale = speed;
  options.record_dir = dir / "recording";
  std::string error;
  auto rt = Runtime::Create(config, options, &error);
  ASSERT_NE(rt, nullptr) << error;

  auto participant = ipc::Participant::Create(config.ipc, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto subscriber = ipc::Subscriber::Create(*participant, config.ipc, {}, &error);
  ASSERT_NE(subscriber, nullptr) << error;

  rt->Start();
  sim::LiveOptions live;
  live.msop_port = rt->msop_port();
  live.difop_port = rt->difop_port();
  live.speed = speed;
  live.pty_link = config.imu.device;
  live.start_delay_s = 0.5;
  live.out_dir = dir / "sim";
  volatile bool stop = false;  // never set: RunLive's flag is for signal handlers, not threads
  sim::LiveStats stats;
  bool sim_ok = false;
  std::atomic<bool> sim_done{false};
  std::thread simulator([&] {
    sim_ok = sim::RunLive(*setup, live, &stop, &stats, &error);
    sim_done = true;
  });
  size_t poses = 0, odometry = 0, health = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool ready = false;
  while (std::chrono::steady_clock::now() < deadline) {
    subscriber->Wait(100'000'000);
    poses += subscriber->TakePoses().size();
    odometry += subscriber->TakeOdometry().size();
    health += subscriber->TakeHealth().size();
    ready = ready || rt->Ready();
    if (sim_done) break;  // the 12 s drive has been streamed
  }
  simulator.join();
  rt->Stop();  // the consumers drain what the rx threads received
  const HealthSnapshot s = rt->Snapshot();
  ASSERT_TRUE(sim_ok) << error;
  EXPECT_TRUE(ready) << "READY condition: sensors stream and the estimator has a state";
  EXPECT_GE(s.optimizer.processed, 90u);
  EXPECT_NE(s.optimizer.tracking, TrackingState::kLost);
  EXPECT_NE(s.optimizer.tracking, TrackingState::kInitializing);
  EXPECT_GE(poses, 1000u) << "IMU-rate poses received over DDS";
  EXPECT_GE(odometry, 70u);
  EXPECT_GE(health, 5u);
  EXPECT_EQ(s.optimizer.lidar.bad_packets, 0u);
  // The recording holds every datagram and serial byte the rx threads received, and reads
  // back through the replay path.
  std::string read_error;
  auto reader =
      RecordingReader::Open(options.record_dir, WithManifestPorts(options.record_dir, config.lidar),
                            config.imu, &read_error);
  ASSERT_NE(reader, nullptr) << read_error;
  RecordingEvent e;
  size_t scans = 0;
  while (reader->Next(&e)) scans += e.kind == RecordingEvent::Kind::kScan ? 1 : 0;
  EXPECT_EQ(reader->stats().lidar_packets, s.optimizer.lidar.data_packets);
  EXPECT_EQ(reader->stats().imu_samples, s.propagator.samples);
  EXPECT_GE(scans, s.optimizer.processed);
  EXPECT_NEAR(ManifestExtrinsic(options.record_dir)->translation().x(),
              setup->lidar.T_imu_lidar.translation().x(), 1e-8);
  // Lossless whenever the simulator delivered everything. On a loaded machine it can fall
  // behind and then write more than the pty holds (it drops and counts those bytes, as a UART
  // would): the daemon must then report them, not hide them.
  const bool fed_everything = stats.imu_bytes_dropped == 0 && stats.udp_errors == 0;
  if (fed_everything) {
    EXPECT_EQ(s.imu_rx.checksum_errors, 0u);
    EXPECT_EQ(s.imu_rx.missing_packets, 0u);
    if (!kSanitized && stats.max_lateness_ms < 50.0) {
      EXPECT_EQ(TotalDrops(s), 0u) << HealthReporter().StatusLine(s);
    }
  } else {
    std::cout << "[ note ] the simulator fell behind (" << stats.max_lateness_ms << " ms, "
              << stats.imu_bytes_dropped
              << " IMU bytes dropped); daemon: " << HealthReporter().StatusLine(s) << "\n";
    EXPECT_GT(s.imu_rx.missing_packets + s.imu_rx.checksum_errors + s.imu_rx.skipped_bytes +
                  s.optimizer.lidar.missing_packets,
              0u)
        << "what the simulator dropped shows in the health";
  }
}

}  // namespace
}  // namespace swlio::daemon

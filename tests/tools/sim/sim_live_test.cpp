// Live mode: the same streams as a file recording, over UDP to 127.0.0.1 and a pty.

#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "live/sim_live.h"
#include "recording/sim_recording.h"
#include "swlio/drivers/udp_receiver.h"
#include "test_data.h"
#include "udp_port.h"

namespace swlio::sim {
namespace {

/// Streams 1 s of `short` live and checks that the same packets and bytes arrive as a file
/// recording of the drive holds.
void ExpectEveryPacketAndFrameArrives(bool precast) {
  constexpr double kDuration = 1.0;
  std::string error;
  drivers::UdpReceiverOptions uo;
  uo.bind_address = "127.0.0.1";
  uo.port = test::QuietUdpPort();
  auto msop = drivers::UdpReceiver::Open(uo, &error);
  uo.port = test::QuietUdpPort();
  auto difop = drivers::UdpReceiver::Open(uo, &error);
  ASSERT_TRUE(msop && difop) << error;

  const auto dir = test::MakeTempDir("live");
  LiveOptions options;
  options.msop_port = msop->bound_port();
  options.difop_port = difop->bound_port();
  options.speed = 2.0;
  options.pty_link = (dir / "imu.pty").string();
  options.out_dir = dir;
  options.start_delay_s = 0.5;
  options.precast = precast;
  auto setup = MakeSimSetup("short", 11, kDuration);
  ASSERT_TRUE(setup);
  volatile bool stop = false;
  LiveStats stats;
  std::atomic<bool> done{false};
  bool ok = false;
  std::thread sender([&] {
    ok = RunLive(*setup, options, &stop, &stats, &error);
    done = true;
  });
  int pty = -1;
  for (int i = 0; i < 200 && pty < 0; ++i) {  // the link appears before streaming starts
    pty = open(options.pty_link.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY);
    if (pty < 0) usleep(5000);
  }
  ASSERT_GE(pty, 0);
  size_t msop_count = 0, difop_count = 0, imu_bytes = 0;
  auto drain = [&] {
    msop_count += msop->Receive(5).size();
    difop_count += difop->Receive(0).size();
    uint8_t buf[4096];
    for (ssize_t n; (n = read(pty, buf, sizeof buf)) > 0;) imu_bytes += static_cast<size_t>(n);
  };
  while (!done) drain();
  sender.join();
  for (int i = 0; i < 20; ++i) drain();
  close(pty);
  ASSERT_TRUE(ok) << error;

  RecordingStats file_stats;  // the same run written to files, for comparison
  ASSERT_TRUE(
      WriteRecording(*MakeSimSetup("short", 11, kDuration), dir / "file", &file_stats, &error));
  EXPECT_EQ(msop_count, file_stats.msop_packets);
  EXPECT_EQ(difop_count, file_stats.difop_packets);
  EXPECT_EQ(imu_bytes, std::filesystem::file_size(dir / "file" / "imu.xbus"));
  EXPECT_EQ(stats.imu_bytes_dropped, 0u);
  EXPECT_EQ(stats.udp_errors, 0u);
  EXPECT_TRUE(std::filesystem::exists(dir / "groundtruth.tum"));
  EXPECT_TRUE(std::filesystem::exists(dir / "manifest.yaml"));
}

TEST(SimLive, StreamsEveryPacketAndFrameToLoopbackAndPty) {
  ExpectEveryPacketAndFrameArrives(false);
}

TEST(SimLive, PrecastStreamsTheSamePacketsAndFrames) { ExpectEveryPacketAndFrameArrives(true); }

// A simulator held up for 400 ms before its first send: the samples due in its first 0.6 s of
// driving (at 2x) go out late, in one span from the start whose worst lateness is the hold-up.
TEST(SimLive, LateSpansMarkWhereTheSimulatorFellBehind) {
  std::string error;
  drivers::UdpReceiverOptions uo;
  uo.bind_address = "127.0.0.1";
  uo.port = test::QuietUdpPort();
  auto msop = drivers::UdpReceiver::Open(uo, &error);
  uo.port = test::QuietUdpPort();  // bound too: nothing is sent to a port another test may hold
  auto difop = drivers::UdpReceiver::Open(uo, &error);
  ASSERT_TRUE(msop && difop) << error;
  const auto dir = test::MakeTempDir("live-late");
  LiveOptions options;
  options.msop_port = msop->bound_port();
  options.difop_port = difop->bound_port();
  options.speed = 2.0;
  options.pty_link = (dir / "imu.pty").string();
  options.precast = true;
  options.on_start = [](int64_t) { std::this_thread::sleep_for(std::chrono::milliseconds(400)); };
  auto setup = MakeSimSetup("short", 11, 1.0);
  ASSERT_TRUE(setup);
  volatile bool stop = false;
  LiveStats stats;
  ASSERT_TRUE(RunLive(*setup, options, &stop, &stats, &error)) << error;
  ASSERT_FALSE(stats.late_spans.empty());
  const LiveStats::LateSpan& first = stats.late_spans.front();
  EXPECT_LT(first.from_s, 0.01);  // the first sample
  // Sent 400 ms after the start, a sample due at t s of driving (t / 2 s of host time) is more
  // than 100 ms late up to t = 0.6 s, less what catching up takes.
  EXPECT_GT(first.to_s, 0.2);
  EXPECT_LT(first.to_s, 0.8);
  // The hold-up less when the first sample was due: its time of driving (a LiDAR packet every
  // 1.2 ms, the first IMU frame after its serial delay) at 2x, under a millisecond.
  EXPECT_GE(first.worst_ms, 399.0);
  EXPECT_LT(first.worst_ms, 1000.0);
  EXPECT_GE(stats.max_lateness_ms, first.worst_ms - 0.01);  // that one is kept as a float
  EXPECT_EQ(stats.WorstLatenessMs(0.0, 0.05), first.worst_ms);
}

TEST(SimLive, WorstLatenessIsThatOfTheSpansOverlappingTheInterval) {
  LiveStats stats;
  stats.late_spans = {{1.0, 2.0, 300.0}, {5.0, 5.5, 150.0}, {6.0, 9.0, 2000.0}};
  EXPECT_EQ(stats.WorstLatenessMs(0.0, 0.9), 0.0);
  EXPECT_EQ(stats.WorstLatenessMs(0.0, 1.0), 300.0);
  EXPECT_EQ(stats.WorstLatenessMs(2.0, 5.2), 300.0);
  EXPECT_EQ(stats.WorstLatenessMs(2.1, 5.2), 150.0);
  EXPECT_EQ(stats.WorstLatenessMs(3.0, 7.0), 2000.0);
  EXPECT_EQ(stats.WorstLatenessMs(9.1, 20.0), 0.0);
}

}  // namespace
}  // namespace swlio::sim

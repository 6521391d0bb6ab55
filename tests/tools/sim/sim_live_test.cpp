// Live mode: the same streams as a file recording, over UDP to 127.0.0.1 and a pty.

#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
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

}  // namespace
}  // namespace swlio::sim

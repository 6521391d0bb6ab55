// The can_rx thread over a socketpair (the test kernel has no CAN): frames are counted, wheel
// odometry decoded (and sent to the optimizer), bad records counted, and the recorder writes
// them in candump format.

#include "swlio/daemon/sensors/can_rx.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "swlio/daemon/recording/recorder.h"
#include "swlio/drivers/candump_log.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

drivers::CanConfig WheelLayout() {
  drivers::CanConfig c;
  c.enabled = true;
  c.interface = "can0";
  c.mode = "wheel_speeds";
  drivers::CanSignalConfig left;
  left.role = "left_wheel_speed";
  left.can_id = 0x201;
  left.start_bit = 0;
  left.length_bits = 16;
  left.byte_order = "intel";
  left.scale = 0.001;
  drivers::CanSignalConfig right = left;
  right.role = "right_wheel_speed";
  right.start_bit = 16;
  c.signals = {left, right};
  return c;
}

void Send(int fd, uint32_t id, std::initializer_list<uint8_t> bytes) {
  drivers::CanFrame f;
  f.id = id;
  f.dlc = static_cast<uint8_t>(bytes.size());
  size_t i = 0;
  for (uint8_t b : bytes) f.data[i++] = b;
  const can_frame raw = drivers::ToSocketCan(f);
  ASSERT_EQ(write(fd, &raw, sizeof raw), static_cast<ssize_t>(sizeof raw));
}

TEST(CanRx, CountsDecodesAndRecordsFrames) {
  int fds[2];
  ASSERT_EQ(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds), 0);
  std::string error;
  auto rx = CanRx::Create(WheelLayout(), fds[0], &error);
  ASSERT_NE(rx, nullptr) << error;
  DaemonConfig config;
  config.can = WheelLayout();
  const auto dir = test::MakeTempDir("can_rx");
  auto recorder = Recorder::Create(dir, config, Eigen::Isometry3d::Identity(), {}, &error);
  ASSERT_NE(recorder, nullptr) << error;
  rx->RecordTo(&recorder->can_queue());
  SpscQueue<WheelOdometry> wheel{"wheel_odometry", "can_rx", "test", 64};
  rx->SendTo(&wheel);
  std::atomic<bool> stop{false}, stop_recorder{false};
  std::thread reader([&] { rx->Run(stop, {}); });
  std::thread writer([&] { recorder->Run(stop_recorder, {}); });
  for (int i = 0; i < 50; ++i) Send(fds[1], 0x201, {0xE8, 0x03, 0xD0, 0x07});  // 1.0, 2.0 m/s
  Send(fds[1], 0x300, {0x01});                                                 // not ours
  const char junk[3] = {1, 2, 3};
  ASSERT_EQ(write(fds[1], junk, sizeof junk), 3);  // not a can_frame record
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while ((rx->counters().frames < 50 || rx->counters().bad_frames < 1) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  close(fds[1]);  // the interface goes away
  while (!rx->counters().closed && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  stop = true;
  reader.join();
  stop_recorder = true;
  writer.join();
  close(fds[0]);
  const CanRxCounters c = rx->counters();
  EXPECT_EQ(c.frames, 50u) << "0x300 is filtered out (the kernel does it on a CAN socket)";
  EXPECT_EQ(c.odometry_samples, 50u);
  EXPECT_EQ(c.unknown_id, 1u);
  EXPECT_EQ(c.bad_frames, 1u);
  EXPECT_TRUE(c.closed);
  std::ifstream log(dir / "can.log");
  drivers::CandumpReader candump(log);
  drivers::CandumpRecord record;
  size_t lines = 0;
  while (candump.Next(&record)) {
    ++lines;
    EXPECT_EQ(record.interface_name(), "can0");
  }
  EXPECT_EQ(lines, 50u);
  EXPECT_FALSE(recorder->counters().stopped) << recorder->counters().error;
  // Every decoded sample also went to the optimizer's queue: v = (1 + 2) / 2, ω = (2 − 1) / b.
  WheelOdometry w;
  size_t samples = 0;
  while (wheel.Pop(&w)) {
    ++samples;
    EXPECT_NEAR(w.linear_velocity_mps, 1.5, 1e-9);
    EXPECT_NEAR(w.yaw_rate_radps, 1.0 / WheelLayout().track_width_m, 1e-9);
    EXPECT_GT(w.t_ns, 0);
  }
  EXPECT_EQ(samples, 50u);
}

}  // namespace
}  // namespace swlio::daemon

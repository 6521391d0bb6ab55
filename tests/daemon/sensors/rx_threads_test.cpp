// The rx threads: every datagram / Xbus sample arrives in the queue with its receive time, what
// cannot be taken is counted, and the steady state allocates nothing (design.md: "no
// allocation after start-up").

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>
#include <vector>

#include "allocation_counter.h"
#include "recording/sim_recording.h"
#include "swlio/daemon/pipeline/propagator_thread.h"
#include "swlio/daemon/sensors/imu_rx.h"
#include "swlio/daemon/sensors/lidar_rx.h"
#include "test_data.h"
#include "udp_port.h"

namespace swlio::daemon {
namespace {

/// Sends `bytes` to 127.0.0.1:port.
void SendTo(int fd, uint16_t port, const std::vector<uint8_t>& bytes) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to),
            static_cast<ssize_t>(bytes.size()));
}

/// Pops until `n` elements came or 5 s passed; returns how many.
template <class T>
size_t PopN(SpscQueue<T>& q, size_t n, std::vector<T>* out = nullptr) {
  size_t got = 0;
  T v;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (got < n && std::chrono::steady_clock::now() < deadline) {
    if (!q.WaitPop(&v, 10'000)) continue;
    if (out != nullptr && out->size() < out->capacity()) out->push_back(v);
    ++got;
  }
  return got;
}

TEST(LidarRx, QueuesEveryDatagramWithoutAllocating) {
  drivers::LidarConfig config;
  config.bind_address = "127.0.0.1";
  config.msop_port = test::QuietUdpPort();
  config.difop_port = test::QuietUdpPort();
  SpscQueue<LidarPacket> q("lidar_packets", "lidar_rx", "test", 4096);
  std::string error;
  auto rx = LidarRx::Open(config, &q, &error);
  ASSERT_NE(rx, nullptr) << error;
  std::atomic<bool> stop{false};
  std::thread t([&] { rx->Run(stop, {}); });
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  std::vector<uint8_t> msop(1248, 0x11), difop(1248, 0x22), huge(2000, 0x33);
  for (int i = 0; i < 100; ++i) SendTo(fd, rx->msop_port(), msop);  // warm-up
  ASSERT_EQ(PopN(q, 100), 100u);
  const int64_t before = test::HeapAllocations();
  for (int i = 0; i < 500; ++i) {
    SendTo(fd, rx->msop_port(), msop);
    if (i % 100 == 0) SendTo(fd, rx->difop_port(), difop);
  }
  const size_t got = PopN(q, 505);
  const int64_t allocations = test::HeapAllocations() - before;
  EXPECT_EQ(got, 505u);
  EXPECT_EQ(allocations, 0) << "heap allocations while 505 datagrams went through";
  SendTo(fd, rx->difop_port(), huge);
  SendTo(fd, rx->difop_port(), difop);
  std::vector<LidarPacket> last;
  last.reserve(1);
  ASSERT_EQ(PopN(q, 1, &last), 1u);
  EXPECT_TRUE(last[0].difop);
  EXPECT_EQ(last[0].size, 1248);
  EXPECT_EQ(last[0].bytes[0], 0x22);
  EXPECT_GT(last[0].t_rx_ns, 0);
  stop = true;
  t.join();
  close(fd);
  EXPECT_EQ(rx->counters().truncated, 1u) << "the 2000-byte datagram is dropped and counted";
  EXPECT_EQ(rx->counters().datagrams, 100u + 505u + 2u);
}

// The reader only reads, stamps and hands over: while the propagator side is not running,
// every byte written waits in the queue, undecoded, with its read time and the port's open
// epoch, and nothing is allocated on the way. The samples and the decoding counters appear only
// once a PropagatorThread consumes the queue.
TEST(ImuRx, HandsOverTheBytesUndecodedWithoutAllocating) {
  int master = -1, slave = -1;
  char name[256] = {};
  if (openpty(&master, &slave, name, nullptr, nullptr) != 0) GTEST_SKIP() << "no pty";
  drivers::ImuConfig config;
  config.device = name;
  config.configure_on_start = false;
  SpscQueue<SerialChunk> q("imu_serial", "imu_rx", "propagator", 4096);
  ImuRx rx(config, &q);
  std::atomic<bool> stop{false};
  std::thread t([&] { rx.Run(stop, {}); });
  std::vector<uint8_t> written;
  written.reserve(600 * 64);
  std::vector<uint8_t> frame(256);
  auto write_samples = [&](int first, int n) {
    for (int k = first; k < first + n; ++k) {
      sim::SimImuSample s;
      s.sample_time_fine = static_cast<uint32_t>(1000 + 25 * k);
      s.packet_counter = static_cast<uint16_t>(k);
      s.acc_mps2 = Eigen::Vector3d(0.1, 0.2, 9.8);
      s.gyro_radps = Eigen::Vector3d(0.01, 0.0, -0.01);
      const size_t size = sim::EncodeImuFrame(s, frame);
      ASSERT_EQ(write(master, frame.data(), size), static_cast<ssize_t>(size));
      written.insert(written.end(), frame.begin(), frame.begin() + static_cast<long>(size));
    }
  };
  auto wait_for_bytes = [&](size_t n) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (rx.counters().bytes < n && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return rx.counters().bytes;
  };
  // The port opens the device within its re-open interval; write once it streams.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!rx.counters().streaming && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  write_samples(0, 100);
  ASSERT_EQ(wait_for_bytes(written.size()), written.size());
  const int64_t before = test::HeapAllocations();
  write_samples(100, 400);  // `written` has its capacity: no allocation here either
  ASSERT_EQ(wait_for_bytes(written.size()), written.size());
  const int64_t allocations = test::HeapAllocations() - before;
  stop = true;
  t.join();
  close(master);
  close(slave);
  EXPECT_EQ(allocations, 0) << "heap allocations while 400 samples were read";

  // Everything waits in the queue, byte for byte, in read order.
  const QueueCounters qc = q.Counters();
  EXPECT_EQ(qc.dropped, 0u);
  EXPECT_EQ(rx.counters().chunks, qc.depth);
  std::vector<SerialChunk> chunks(qc.depth);
  std::vector<uint8_t> handed;
  for (SerialChunk& c : chunks) {
    ASSERT_TRUE(q.Pop(&c));
    EXPECT_EQ(c.epoch, 1u);
    EXPECT_GT(c.t_rx_ns, 0);
    handed.insert(handed.end(), c.bytes.begin(), c.bytes.begin() + c.size);
  }
  EXPECT_EQ(handed, written);
  for (size_t i = 1; i < chunks.size(); ++i) EXPECT_GE(chunks[i].t_rx_ns, chunks[i - 1].t_rx_ns);

  // The propagator side decodes them.
  SpscQueue<SerialChunk> serial("imu_serial", "test", "propagator", 4096);
  SpscQueue<SweepEstimate> states("states", "test", "propagator", 16);
  SpscQueue<ImuSample> samples("imu_samples", "propagator", "test", 1024);
  SpscQueue<ImuRatePose> poses("poses", "propagator", "test", 16);
  PropagatorThread propagator(921600, estimator::ImuRatePropagatorConfig{},
                              PropagatorQueues{&serial, &states, &samples, &poses});
  EXPECT_EQ(propagator.counters().decode.samples, 0u);
  for (const SerialChunk& c : chunks) ASSERT_TRUE(serial.Push(c));
  std::atomic<bool> stop_propagator{false};
  std::thread p([&] { propagator.Run(stop_propagator, {}); });
  // (The writes came in a burst, 2.5 ms of sensor time apart: the clock model drops most of
  // them as mapped to the past; only the decoding is checked here.)
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (propagator.counters().decode.samples < 500 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  stop_propagator = true;
  p.join();
  const PropagatorCounters pc = propagator.counters();
  EXPECT_EQ(pc.decode.samples, 500u);
  EXPECT_EQ(pc.decode.checksum_errors, 0u);
  EXPECT_EQ(pc.decode.skipped_bytes, 0u);
  EXPECT_EQ(pc.decode.missing_packets, 0u);
  EXPECT_EQ(pc.decode.restarts, 0u);
  EXPECT_GT(pc.samples, 0u);
}

}  // namespace
}  // namespace swlio::daemon

#include "swlio/drivers/udp_receiver.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <vector>

#include "swlio/drivers/rx_timestamp.h"
#include "udp_port.h"

namespace swlio::drivers {
namespace {

/// Sends datagrams to 127.0.0.1:port from a fresh UDP socket.
class LoopbackSender {
 public:
  explicit LoopbackSender(uint16_t port) : fd_(socket(AF_INET, SOCK_DGRAM, 0)) {
    to_.sin_family = AF_INET;
    to_.sin_port = htons(port);
    to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  }
  ~LoopbackSender() { close(fd_); }
  bool Send(const std::vector<uint8_t>& payload) {
    return sendto(fd_, payload.data(), payload.size(), 0, reinterpret_cast<sockaddr*>(&to_),
                  sizeof(to_)) == static_cast<ssize_t>(payload.size());
  }

 private:
  int fd_;
  sockaddr_in to_{};
};

UdpReceiver OpenLoopback(size_t batch, size_t max_bytes, int64_t rcvbuf = 1 << 20) {
  UdpReceiverOptions o;
  o.bind_address = "127.0.0.1";
  o.port = test::QuietUdpPort();
  o.batch_size = batch;
  o.max_datagram_bytes = max_bytes;
  o.rcvbuf_bytes = rcvbuf;
  std::string error;
  auto r = UdpReceiver::Open(o, &error);
  EXPECT_TRUE(r) << error;
  return std::move(*r);
}

std::vector<uint8_t> Payload(size_t size, uint8_t seed) {
  std::vector<uint8_t> p(size);
  for (size_t i = 0; i < size; ++i) p[i] = static_cast<uint8_t>(seed + i * 7);
  return p;
}

TEST(UdpReceiver, ReceivesBatchesWithKernelTimestampsInOrder) {
  UdpReceiver rx = OpenLoopback(8, 1500);
  ASSERT_NE(rx.bound_port(), 0);
  EXPECT_TRUE(rx.kernel_timestamps());
  LoopbackSender tx(rx.bound_port());
  const int64_t before = MonotonicNowNs();
  for (uint8_t i = 0; i < 20; ++i) ASSERT_TRUE(tx.Send(Payload(1248, i)));
  const int64_t after_send = MonotonicNowNs();
  std::vector<std::vector<uint8_t>> got;
  int64_t last_t = 0;
  for (int round = 0; round < 10 && got.size() < 20; ++round) {
    const auto batch = rx.Receive(1000);
    EXPECT_LE(batch.size(), 8u);
    for (const ReceivedDatagram& d : batch) {
      got.emplace_back(d.payload.begin(), d.payload.end());
      EXPECT_FALSE(d.truncated);
      EXPECT_EQ(d.source_address, INADDR_LOOPBACK);
      EXPECT_EQ(d.kernel_stamp, rx.kernel_timestamps());
      EXPECT_GE(d.t_ns, before - 1'000'000);
      EXPECT_LE(d.t_ns, after_send + 1'000'000);
      EXPECT_GE(d.t_ns, last_t);
      last_t = d.t_ns;
    }
  }
  ASSERT_EQ(got.size(), 20u);
  for (uint8_t i = 0; i < 20; ++i) EXPECT_EQ(got[i], Payload(1248, i)) << int{i};
  EXPECT_EQ(rx.counters().datagrams, 20u);
  EXPECT_GE(rx.counters().batches, 3u);  // 20 datagrams, at most 8 per call
  EXPECT_EQ(rx.counters().errors, 0u);
}

TEST(UdpReceiver, CountsTruncatedDatagrams) {
  UdpReceiver rx = OpenLoopback(4, 100);
  LoopbackSender tx(rx.bound_port());
  ASSERT_TRUE(tx.Send(Payload(100, 1)));
  ASSERT_TRUE(tx.Send(Payload(101, 2)));
  size_t seen = 0;
  std::vector<bool> truncated;
  for (int round = 0; round < 5 && seen < 2; ++round) {
    for (const ReceivedDatagram& d : rx.Receive(1000)) {
      ++seen;
      truncated.push_back(d.truncated);
      EXPECT_EQ(d.payload.size(), 100u);
    }
  }
  ASSERT_EQ(truncated, (std::vector<bool>{false, true}));
  EXPECT_EQ(rx.counters().truncated, 1u);
}

TEST(UdpReceiver, TimesOutWithoutData) {
  UdpReceiver rx = OpenLoopback(4, 100);
  const int64_t t0 = MonotonicNowNs();
  EXPECT_TRUE(rx.Receive(50).empty());
  EXPECT_GE(MonotonicNowNs() - t0, 40'000'000);
  EXPECT_TRUE(rx.Receive(0).empty());
  EXPECT_EQ(rx.counters().errors, 0u);
}

TEST(UdpReceiver, ReportsRequestedAndGrantedReceiveBuffer) {
  UdpReceiver small = OpenLoopback(1, 100, 64 * 1024);
  EXPECT_EQ(small.rcvbuf_requested(), 64 * 1024);
  // Linux doubles the request (socket(7)); either way the granted size is read back.
  EXPECT_GE(small.rcvbuf_granted(), 64 * 1024);
  UdpReceiver big = OpenLoopback(1, 100, 256 * 1024 * 1024);
  EXPECT_EQ(big.rcvbuf_requested(), 256 * 1024 * 1024);
  EXPECT_GT(big.rcvbuf_granted(), 0);
  EXPECT_GT(big.rcvbuf_granted(), small.rcvbuf_granted());
}

TEST(UdpReceiver, RejectsBadOptions) {
  UdpReceiverOptions o;
  o.bind_address = "not-an-address";
  std::string error;
  EXPECT_FALSE(UdpReceiver::Open(o, &error));
  EXPECT_NE(error.find("not-an-address"), std::string::npos);
  o.bind_address = "127.0.0.1";
  o.batch_size = 0;
  EXPECT_FALSE(UdpReceiver::Open(o, &error));
  // Binding a port that is already taken fails with the reason.
  UdpReceiver first = OpenLoopback(1, 100);
  o.batch_size = 1;
  o.port = first.bound_port();
  EXPECT_FALSE(UdpReceiver::Open(o, &error));
  EXPECT_NE(error.find("bind"), std::string::npos);
}

}  // namespace
}  // namespace swlio::drivers

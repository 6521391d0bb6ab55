#include "swlio/drivers/can_reader.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <vector>

#include "swlio/drivers/rx_timestamp.h"
#include "swlio/drivers/wheel_odom_decoder.h"

namespace swlio::drivers {
namespace {

/// A SOCK_SEQPACKET pair: [0] is read by the CanReader, [1] plays the CAN controller.
class CanReaderTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds_), 0); }
  void TearDown() override {
    for (int fd : fds_) {
      if (fd >= 0) close(fd);
    }
  }
  void Send(const CanFrame& f) {
    const can_frame raw = ToSocketCan(f);
    ASSERT_EQ(send(fds_[1], &raw, sizeof(raw), 0), static_cast<ssize_t>(sizeof(raw)));
  }
  static CanFrame Frame(uint32_t id, bool extended, uint8_t first_byte) {
    CanFrame f;
    f.id = id;
    f.extended = extended;
    f.dlc = 2;
    f.data[0] = first_byte;
    f.data[1] = 0xAB;
    return f;
  }
  int fds_[2] = {-1, -1};
};

TEST_F(CanReaderTest, ReadsFramesWithKernelTimestampsOnTheMonotonicClock) {
  CanReader reader(fds_[0], {});
  EXPECT_FALSE(reader.kernel_filtering());
  EXPECT_TRUE(reader.kernel_timestamps());  // SO_TIMESTAMPNS works on AF_UNIX sockets too
  const int64_t before = MonotonicNowNs();
  Send(Frame(0x123, false, 1));
  CanFrame ext = Frame(0x1ABCDEF0, true, 2);
  Send(ext);
  CanFrame remote = Frame(0x7FF, false, 0);
  remote.remote = true;
  remote.dlc = 4;
  Send(remote);
  const int64_t after_send = MonotonicNowNs();
  std::array<CanRxFrame, 8> out{};
  ASSERT_EQ(reader.Read(out, 1000), 3);
  EXPECT_EQ(out[0].frame.id, 0x123u);
  EXPECT_FALSE(out[0].frame.extended);
  EXPECT_EQ(out[0].frame.dlc, 2);
  EXPECT_EQ(out[0].frame.data[0], 1);
  EXPECT_EQ(out[0].frame.data[1], 0xAB);
  EXPECT_EQ(out[1].frame.id, 0x1ABCDEF0u);
  EXPECT_TRUE(out[1].frame.extended);
  EXPECT_TRUE(out[2].frame.remote);
  EXPECT_EQ(out[2].frame.dlc, 4);
  EXPECT_EQ(out[2].frame.data[0], 0);  // a remote frame carries no data
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(out[i].kernel_stamp, reader.kernel_timestamps());
    // The stamp is taken when the kernel queues the frame: after `before`, and (allowing the
    // microseconds of the realtime→monotonic conversion) not after the send returned.
    EXPECT_GE(out[i].t_ns, before - 1'000'000);
    EXPECT_LE(out[i].t_ns, after_send + 1'000'000);
  }
  EXPECT_EQ(reader.counters().frames, 3u);
  EXPECT_EQ(reader.Read(out, 0), 0);  // nothing left: a timeout, not an error
  EXPECT_EQ(reader.counters().read_errors, 0u);
}

TEST_F(CanReaderTest, FiltersIdsLikeTheKernel) {
  const std::array<CanIdFilter, 2> filters = {
      CanIdFilter{0x200, false, 0x7F0},  // 0x200–0x20F, standard only
      CanIdFilter{0x18FF0001, true, kCanMaxExtendedId}};
  CanReader reader(fds_[0], filters);
  Send(Frame(0x205, false, 1));
  Send(Frame(0x210, false, 2));  // outside the mask
  Send(Frame(0x205, true, 3));   // same number, extended: rejected
  Send(Frame(0x18FF0001, true, 4));
  Send(Frame(0x18FF0002, true, 5));
  std::array<CanRxFrame, 8> out{};
  ASSERT_EQ(reader.Read(out, 1000), 2);
  EXPECT_EQ(out[0].frame.data[0], 1);
  EXPECT_EQ(out[1].frame.data[0], 4);
  EXPECT_EQ(reader.counters().filtered_out, 3u);
}

TEST_F(CanReaderTest, CountsRecordsOfTheWrongSizeAndReportsTheEnd) {
  CanReader reader(fds_[0], {});
  const std::array<uint8_t, 72> canfd{};  // a CAN FD-sized record
  ASSERT_EQ(send(fds_[1], canfd.data(), canfd.size(), 0), 72);
  ASSERT_EQ(send(fds_[1], canfd.data(), 5, 0), 5);
  can_frame bad_len = ToSocketCan(Frame(0x1, false, 0));
  bad_len.len = 9;
  ASSERT_EQ(send(fds_[1], &bad_len, sizeof(bad_len), 0), static_cast<ssize_t>(sizeof(bad_len)));
  Send(Frame(0x42, false, 7));
  std::array<CanRxFrame, 4> out{};
  ASSERT_EQ(reader.Read(out, 1000), 1);
  EXPECT_EQ(out[0].frame.id, 0x42u);
  EXPECT_EQ(reader.counters().bad_size, 3u);
  close(fds_[1]);
  fds_[1] = -1;
  EXPECT_EQ(reader.Read(out, 1000), -1);
  EXPECT_EQ(reader.counters().closed, 1u);
}

TEST_F(CanReaderTest, BatchesAreBoundedByTheCallersBuffer) {
  CanReader reader(fds_[0], {});
  for (uint8_t i = 0; i < 10; ++i) Send(Frame(0x100, false, i));
  std::array<CanRxFrame, 4> out{};
  std::vector<int> seen;
  for (int round = 0; round < 5 && seen.size() < 10; ++round) {
    const int n = reader.Read(out, 100);
    ASSERT_GE(n, 0);
    ASSERT_LE(n, 4);
    for (int i = 0; i < n; ++i) seen.push_back(out[static_cast<size_t>(i)].frame.data[0]);
  }
  ASSERT_EQ(seen.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(seen[static_cast<size_t>(i)], i);
}

TEST(CanSocket, OpeningAMissingInterfaceFailsWithAReason) {
  // This kernel has no CAN support (socket() fails); with CAN, the name does not exist.
  std::string error;
  EXPECT_EQ(OpenCanRawSocket("nocan9", &error), -1);
  EXPECT_FALSE(error.empty());
}

TEST(SocketCanConversion, RoundTripsFlagsAndData) {
  CanFrame f;
  f.id = 0x1FFFFFFF;
  f.extended = true;
  f.dlc = 8;
  for (size_t i = 0; i < 8; ++i) f.data[i] = static_cast<uint8_t>(0xF0 + i);
  const can_frame raw = ToSocketCan(f);
  EXPECT_EQ(raw.can_id, 0x9FFFFFFFu);  // CAN_EFF_FLAG | id
  const CanFrame back = FromSocketCan(raw);
  EXPECT_EQ(back.id, f.id);
  EXPECT_TRUE(back.extended);
  EXPECT_EQ(back.data, f.data);
}

}  // namespace
}  // namespace swlio::drivers

namespace swlio::drivers {
namespace {

TEST_F(CanReaderTest, FeedsTheDecoderThroughFiltersBuiltFromItsLayout) {
  CanConfig layout;
  for (const char* role : {"left_wheel_speed", "right_wheel_speed"}) {
    CanSignalConfig s;
    s.role = role;
    s.can_id = layout.signals.empty() ? 0x301 : 0x302;
    s.byte_offset = 0;
    s.length_bits = 16;
    s.scale = 0.001;
    layout.signals.push_back(s);
  }
  auto decoder = WheelOdomDecoder::Create(layout);
  ASSERT_TRUE(decoder);
  std::vector<CanIdFilter> filters;
  for (int i = 0; i < decoder->NumIds(); ++i) {
    filters.push_back({decoder->IdSignal(i).id, decoder->IdSignal(i).extended, kCanMaxExtendedId});
  }
  ASSERT_EQ(filters.size(), 2u);
  CanReader reader(fds_[0], filters);
  for (int k = 0; k < 5; ++k) {
    Send(Frame(0x100, false, 0xEE));  // chassis chatter the filter removes
    Send(Frame(0x301, false, static_cast<uint8_t>(10 + k)));
    Send(Frame(0x302, false, static_cast<uint8_t>(20 + k)));
  }
  std::array<CanRxFrame, 16> out{};
  std::vector<WheelOdomSample> samples;
  for (int round = 0; round < 5 && samples.size() < 5; ++round) {
    const int n = reader.Read(out, 200);
    for (int i = 0; i < n; ++i) {
      const CanRxFrame& rx = out[static_cast<size_t>(i)];
      if (auto s = decoder->Decode(rx.frame, rx.t_ns)) samples.push_back(*s);
    }
  }
  ASSERT_EQ(samples.size(), 5u);
  for (size_t k = 0; k < 5; ++k) {
    // Frame() puts 0xAB in byte 1: raw = 0xAB00 + first byte, signed → negative.
    EXPECT_DOUBLE_EQ(samples[k].left_wheel_mps, (static_cast<int16_t>(0xAB00 + 10 + k)) * 0.001);
    EXPECT_DOUBLE_EQ(samples[k].right_wheel_mps, (static_cast<int16_t>(0xAB00 + 20 + k)) * 0.001);
  }
  EXPECT_EQ(reader.counters().filtered_out, 5u);
  EXPECT_EQ(decoder->counters().unknown_id, 0u);
}

}  // namespace
}  // namespace swlio::drivers

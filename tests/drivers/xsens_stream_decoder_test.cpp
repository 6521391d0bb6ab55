// XsensStreamDecoder: MTData2 samples from serial chunks of any split, each with the time of
// the chunk that completed its frame; checksum errors and PacketCounter gaps counted; a new
// epoch (the device opened again) drops the old stream's partial frame and its counter.

#include "swlio/drivers/xsens/xsens_stream_decoder.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"
#include "xsens_test_util.h"

namespace swlio::drivers::xsens {
namespace {

/// The Xbus frame of an MTData2 message with `counter` and inertial items.
std::vector<uint8_t> SampleFrame(uint16_t counter) {
  const std::vector<uint8_t> payload = test::LevelSamplePayload(counter);
  std::vector<uint8_t> frame(kXbusMaxFrame);
  frame.resize(EncodeXbusFrame(mid::kMtData2, payload, frame));
  return frame;
}

void Append(std::vector<uint8_t>* out, const std::vector<uint8_t>& bytes) {
  out->insert(out->end(), bytes.begin(), bytes.end());
}

class XsensStreamDecoderTest : public ::testing::Test {
 protected:
  XsensStreamDecoderTest()
      : decoder_([this](const MtData2Sample& s, int64_t t) {
          counters_.push_back(s.packet_counter.value_or(0xFFFF));
          times_.push_back(t);
        }) {}

  /// Feeds `bytes` in chunks of `chunk` bytes, chunk i read at time 1000 + i.
  void FeedInChunks(std::span<const uint8_t> bytes, size_t chunk, uint32_t epoch) {
    for (size_t pos = 0; pos < bytes.size(); pos += chunk, ++t_) {
      decoder_.Process(bytes.subspan(pos, std::min(chunk, bytes.size() - pos)), t_, epoch);
    }
  }

  XsensStreamDecoder decoder_;
  std::vector<uint16_t> counters_;
  std::vector<int64_t> times_;
  int64_t t_ = 1000;
};

TEST_F(XsensStreamDecoderTest, FramesSplitAcrossChunksTakeTheTimeOfTheirLastByte) {
  const std::vector<uint8_t> frame = SampleFrame(7);
  ASSERT_GT(frame.size(), 10u);
  std::vector<uint8_t> bytes;
  for (uint16_t c = 1; c <= 5; ++c) Append(&bytes, SampleFrame(c));
  for (const size_t chunk : {size_t{1}, size_t{3}, frame.size() - 1, size_t{1000}}) {
    counters_.clear();
    times_.clear();
    const int64_t t0 = t_;
    FeedInChunks(bytes, chunk, 1);
    ASSERT_EQ(counters_, (std::vector<uint16_t>{1, 2, 3, 4, 5})) << "chunks of " << chunk;
    for (size_t i = 0; i < times_.size(); ++i) {
      const size_t last_byte = (i + 1) * frame.size() - 1;
      EXPECT_EQ(times_[i], t0 + static_cast<int64_t>(last_byte / chunk)) << "chunks of " << chunk;
    }
  }
  EXPECT_EQ(decoder_.stats().samples, 20u);
  EXPECT_EQ(decoder_.last_frame_bytes(), frame.size());
  // The counter ran 1..5 four times: each wrap back to 1 is a discontinuity, not a loss.
  EXPECT_EQ(decoder_.stats().counter_gaps, 3u);
  EXPECT_EQ(decoder_.stats().missing_packets, 0u);
  EXPECT_EQ(decoder_.stats().framer.checksum_errors, 0u);
  EXPECT_EQ(decoder_.stats().framer.skipped_bytes, 0u);
  EXPECT_EQ(decoder_.stats().restarts, 0u);
}

TEST_F(XsensStreamDecoderTest, CountsChecksumErrorsAndLostPackets) {
  std::vector<uint8_t> bytes;
  for (uint16_t c = 1; c <= 3; ++c) Append(&bytes, SampleFrame(c));
  std::vector<uint8_t> broken = SampleFrame(4);
  broken[broken.size() / 2] ^= 0x01;  // checksum no longer sums to 0
  Append(&bytes, broken);
  Append(&bytes, SampleFrame(5));
  Append(&bytes, SampleFrame(9));  // 6, 7, 8 lost
  FeedInChunks(bytes, 17, 1);
  EXPECT_EQ(counters_, (std::vector<uint16_t>{1, 2, 3, 5, 9}));
  const XsensStreamStats& s = decoder_.stats();
  EXPECT_EQ(s.samples, 5u);
  EXPECT_GE(s.framer.checksum_errors, 1u);
  EXPECT_GE(s.framer.skipped_bytes, broken.size());
  EXPECT_EQ(s.counter_gaps, 2u);
  EXPECT_EQ(s.missing_packets, 1u + 3u);
}

TEST_F(XsensStreamDecoderTest, ANewEpochDropsThePartialFrameAndTheCounter) {
  std::vector<uint8_t> first;
  for (uint16_t c = 10; c <= 12; ++c) Append(&first, SampleFrame(c));
  const std::vector<uint8_t> cut = SampleFrame(13);
  first.insert(first.end(), cut.begin(), cut.begin() + 9);  // unplugged mid-frame
  FeedInChunks(first, 5, 1);
  // The device comes back with its counter elsewhere; its first frame is whole. Without the
  // restart the cut frame's 9 bytes would swallow the start of this one.
  std::vector<uint8_t> second;
  for (uint16_t c = 500; c <= 502; ++c) Append(&second, SampleFrame(c));
  FeedInChunks(second, 7, 2);
  EXPECT_EQ(counters_, (std::vector<uint16_t>{10, 11, 12, 500, 501, 502}));
  const XsensStreamStats& s = decoder_.stats();
  EXPECT_EQ(s.restarts, 1u);
  EXPECT_EQ(s.counter_gaps, 0u) << "a new stream is not a gap";
  EXPECT_EQ(s.missing_packets, 0u);
  EXPECT_EQ(s.framer.checksum_errors, 0u);
  EXPECT_EQ(s.framer.skipped_bytes, 9u) << "the cut frame's bytes";
  EXPECT_EQ(s.framer.bytes_in, first.size() + second.size());
  EXPECT_EQ(s.framer.bytes_in, s.framer.bytes_in_frames + s.framer.skipped_bytes);
  // The same epoch again is the same stream: no restart.
  FeedInChunks(SampleFrame(503), 4, 2);
  EXPECT_EQ(decoder_.stats().restarts, 1u);
  EXPECT_EQ(decoder_.stats().counter_gaps, 0u);
}

TEST_F(XsensStreamDecoderTest, OtherMessagesAreCountedNotDelivered) {
  std::vector<uint8_t> bytes(kXbusMaxFrame);
  bytes.resize(EncodeXbusFrame(mid::kError, std::vector<uint8_t>{0x04}, bytes));
  std::vector<uint8_t> ack(kXbusMaxFrame);
  ack.resize(EncodeXbusFrame(mid::kGoToMeasurementAck, {}, ack));
  Append(&bytes, ack);
  Append(&bytes, SampleFrame(1));
  FeedInChunks(bytes, 64, 1);
  EXPECT_EQ(counters_, (std::vector<uint16_t>{1}));
  EXPECT_EQ(decoder_.stats().error_messages, 1u);
  EXPECT_EQ(decoder_.stats().other_messages, 1u);
}

}  // namespace
}  // namespace swlio::drivers::xsens

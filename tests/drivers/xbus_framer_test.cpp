// Xbus framer: resynchronization on garbage, split reads, streams cut mid-frame, extended
// length, oversize headers, the frame encoder; real einride MTi-G-710 capture where it helps.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"
#include "test_data.h"
#include "xsens_test_util.h"

namespace swlio::drivers::xsens {
namespace {

using test::CollectFrames;
using test::OwnedFrame;

std::vector<uint8_t> Frame(uint8_t mid, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> out(kXbusMaxFrame);
  out.resize(EncodeXbusFrame(mid, payload, out));
  return out;
}

uint16_t CounterOf(const OwnedFrame& f) {
  MtData2Sample s;
  EXPECT_EQ(DecodeMtData2(f.payload, &s), MtData2Status::kOk);
  return s.packet_counter.value_or(0);
}

TEST(XbusEncode, KnownGoToConfigBytes) {
  // MT0101P example messages: GoToConfig = FA FF 30 00 D1, ReqDID = FA FF 00 00 01.
  EXPECT_EQ(Frame(mid::kGoToConfig, {}), (std::vector<uint8_t>{0xFA, 0xFF, 0x30, 0x00, 0xD1}));
  EXPECT_EQ(Frame(mid::kReqDid, {}), (std::vector<uint8_t>{0xFA, 0xFF, 0x00, 0x00, 0x01}));
}

TEST(XbusEncode, RefusesSmallBufferAndHugePayload) {
  std::vector<uint8_t> payload(10, 0x11);
  std::vector<uint8_t> out(14);
  EXPECT_EQ(EncodeXbusFrame(0x36, payload, out), 0u);
  std::vector<uint8_t> huge(kXbusMaxPayload + 1);
  std::vector<uint8_t> big_out(kXbusMaxFrame + 10);
  EXPECT_EQ(EncodeXbusFrame(0x36, huge, big_out), 0u);
}

TEST(XbusFramer, ExtendedLengthFramesRoundTrip) {
  std::vector<uint8_t> stream;
  for (size_t len : {0u, 1u, 254u, 255u, 300u, 2048u}) {
    std::vector<uint8_t> payload(len);
    for (size_t i = 0; i < len; ++i) payload[i] = static_cast<uint8_t>(i * 7 + len);
    const auto f = Frame(0x36, payload);
    ASSERT_EQ(f.size(), (len >= 255 ? 6u : 4u) + len + 1);
    if (len >= 255) {
      EXPECT_EQ(f[3], 0xFF);
    }
    stream.insert(stream.end(), f.begin(), f.end());
  }
  XbusFramerStats stats;
  const auto frames = CollectFrames(stream, 97, &stats);
  ASSERT_EQ(frames.size(), 6u);
  EXPECT_EQ(frames[4].payload.size(), 300u);
  EXPECT_EQ(frames[5].payload.size(), 2048u);
  EXPECT_EQ(frames[5].payload[100], static_cast<uint8_t>(100 * 7 + 2048));
  EXPECT_EQ(stats.skipped_bytes, 0u);
  EXPECT_EQ(stats.checksum_errors, 0u);
}

TEST(XbusFramer, OversizeHeaderIsCountedAndSkipped) {
  std::vector<uint8_t> stream = {0xFA, 0xFF, 0x36, 0xFF, 0x0B, 0xB8};  // announces 3000 bytes
  const auto good = Frame(0x31, {});
  stream.insert(stream.end(), good.begin(), good.end());
  XbusFramerStats stats;
  const auto frames = CollectFrames(stream, 1, &stats);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].mid, 0x31);
  EXPECT_EQ(stats.oversize, 1u);
  EXPECT_EQ(stats.skipped_bytes, 6u);
}

TEST(XbusFramer, BadChecksumCostsOnlyThatFrame) {
  auto bad = Frame(0x36, {1, 2, 3, 4});
  bad.back() ^= 0x55;
  const auto good = Frame(0x11, {});
  std::vector<uint8_t> stream = bad;
  stream.insert(stream.end(), good.begin(), good.end());
  XbusFramerStats stats;
  const auto frames = CollectFrames(stream, 3, &stats);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].mid, 0x11);
  EXPECT_EQ(stats.checksum_errors, 1u);
  EXPECT_EQ(stats.skipped_bytes, bad.size());
  EXPECT_EQ(stats.bytes_in, stats.bytes_in_frames + stats.skipped_bytes);
}

TEST(XbusFramer, FalsePreambleAnnouncingLongFrameDoesNotSwallowRealFrames) {
  // A garbage header announces 200 bytes; the real frames inside that window must survive.
  std::vector<uint8_t> stream = {0xFA, 0xFF, 0x36, 200};
  for (int i = 0; i < 20; ++i) {
    const auto f = Frame(0x11, {static_cast<uint8_t>(i)});
    stream.insert(stream.end(), f.begin(), f.end());
  }
  stream.resize(stream.size() + 100, 0x00);
  const auto frames = CollectFrames(stream, 5);
  ASSERT_EQ(frames.size(), 20u);
  for (size_t i = 0; i < 20; ++i) EXPECT_EQ(frames[i].payload[0], i);
}

class EinrideStream : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto path = test::DataFile("xsens_einride_mti-g-710/1/output.bin");
    if (path.empty()) GTEST_SKIP() << "einride capture not found under " << test::DataDir();
    bytes_ = test::ReadBytes(path);
    reference_ = CollectFrames(bytes_, bytes_.size());
    ASSERT_EQ(reference_.size(), 100u);
  }
  std::vector<uint8_t> bytes_;
  std::vector<OwnedFrame> reference_;
};

TEST_F(EinrideStream, AnySplitGivesTheSameFrames) {
  for (size_t chunk : {1u, 2u, 3u, 7u, 64u, 1000u}) {
    const auto frames = CollectFrames(bytes_, chunk);
    ASSERT_EQ(frames.size(), reference_.size()) << "chunk " << chunk;
    for (size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(frames[i].wire, reference_[i].wire);
  }
}

TEST_F(EinrideStream, StreamStartedMidFrameLosesOnlyTheCutFrame) {
  const size_t first = reference_[0].wire.size();
  for (size_t cut = 1; cut < first; ++cut) {
    XbusFramerStats stats;
    const auto frames = CollectFrames(std::span<const uint8_t>(bytes_).subspan(cut), 128, &stats);
    ASSERT_EQ(frames.size(), 99u) << "cut at " << cut;
    EXPECT_EQ(frames.front().wire, reference_[1].wire);
    EXPECT_EQ(frames.back().wire, reference_[99].wire);
    EXPECT_EQ(stats.skipped_bytes, first - cut);
  }
}

TEST_F(EinrideStream, RandomGarbageBetweenFramesLosesNothing) {
  std::mt19937 rng(20190120);
  std::vector<uint8_t> stream;
  size_t garbage = 0;
  for (const auto& f : reference_) {
    const size_t n = rng() % 40;
    for (size_t i = 0; i < n; ++i) {
      // Bias towards the preamble and bus id so that false headers really occur.
      const uint32_t r = rng() % 8;
      stream.push_back(r == 0 ? 0xFA : r == 1 ? 0xFF : static_cast<uint8_t>(rng()));
    }
    garbage += n;
    stream.insert(stream.end(), f.wire.begin(), f.wire.end());
  }
  XbusFramerStats stats;
  const auto frames = CollectFrames(stream, 33, &stats);
  ASSERT_EQ(frames.size(), reference_.size());
  for (size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(frames[i].wire, reference_[i].wire);
  EXPECT_EQ(stats.skipped_bytes, garbage);
}

TEST_F(EinrideStream, GarbageInsideFramesLosesOnlyTheDamagedFrames) {
  std::mt19937 rng(7);
  std::vector<uint8_t> stream;
  std::set<uint16_t> expected_counters;
  for (const auto& f : reference_) {
    if (rng() % 4 == 0) {
      // Damage: insert 1–8 random bytes somewhere after the preamble.
      std::vector<uint8_t> damaged = f.wire;
      const size_t at = 1 + rng() % (damaged.size() - 1);
      const size_t n = 1 + rng() % 8;
      for (size_t i = 0; i < n; ++i) {
        damaged.insert(damaged.begin() + static_cast<std::ptrdiff_t>(at),
                       static_cast<uint8_t>(rng()));
      }
      stream.insert(stream.end(), damaged.begin(), damaged.end());
    } else {
      expected_counters.insert(CounterOf(f));
      stream.insert(stream.end(), f.wire.begin(), f.wire.end());
    }
  }
  ASSERT_GT(expected_counters.size(), 50u);
  ASSERT_LT(expected_counters.size(), 100u);
  XbusFramerStats stats;
  const auto frames = CollectFrames(stream, 17, &stats);
  std::set<uint16_t> got;
  for (const auto& f : frames) got.insert(CounterOf(f));
  EXPECT_EQ(got, expected_counters);
  EXPECT_EQ(frames.size(), expected_counters.size());
  EXPECT_GE(stats.checksum_errors + stats.bad_bid + stats.oversize,
            100u - expected_counters.size());
  EXPECT_EQ(stats.bytes_in, stats.bytes_in_frames + stats.skipped_bytes);
}

// A protocol phase ends after a frame (the configuration handshake's last reply): the bytes
// behind it go back out, as if never fed, for the stream's own framer.
TEST(XbusFramer, TakeBufferedGivesBackTheUnframedRest) {
  const std::vector<uint8_t> ack = Frame(mid::kGoToMeasurementAck, {});
  const std::vector<uint8_t> next = Frame(mid::kMtData2, {0x10, 0x20, 0x02, 0x00, 0x07});
  std::vector<uint8_t> bytes = ack;
  bytes.insert(bytes.end(), next.begin(), next.begin() + 6);
  XbusFramer framer;
  ASSERT_EQ(framer.Feed(bytes), bytes.size());
  XbusFrame f;
  ASSERT_TRUE(framer.Next(&f));
  EXPECT_EQ(f.mid, mid::kGoToMeasurementAck);
  const std::span<const uint8_t> rest = framer.TakeBuffered();
  EXPECT_EQ(std::vector<uint8_t>(rest.begin(), rest.end()),
            std::vector<uint8_t>(next.begin(), next.begin() + 6));
  EXPECT_EQ(framer.buffered(), 0u);
  EXPECT_FALSE(framer.Next(&f));
  framer.Flush();
  EXPECT_EQ(framer.stats().bytes_in, ack.size());
  EXPECT_EQ(framer.stats().bytes_in, framer.stats().bytes_in_frames + framer.stats().skipped_bytes);
}

}  // namespace
}  // namespace swlio::drivers::xsens

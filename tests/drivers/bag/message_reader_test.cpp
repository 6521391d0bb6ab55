// The bounded CDR / ROS 1 reader: alignment relative to byte 4, both byte orders, strings with
// and without NUL, sequence bounds, sticky failures with their position, trailing bytes, and
// the writer's output against hand-laid bytes.

#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <vector>

#include "swlio/drivers/bag/message_reader.h"
#include "swlio/drivers/bag/message_writer.h"

namespace swlio::drivers::bag {
namespace {

using Bytes = std::vector<uint8_t>;

void PutF64Be(Bytes& b, size_t at, double v) {
  const auto u = std::bit_cast<uint64_t>(v);
  for (size_t i = 0; i < 8; ++i) b[at + i] = static_cast<uint8_t>(u >> (56 - 8 * i));
}

TEST(MessageReader, CdrAlignsRelativeToByteFour) {
  // u8 at 4, then a float64: aligned to 8 from byte 4, so it starts at byte 12 (≡ 4 mod 8).
  Bytes b = {0x00, 0x01, 0x00, 0x00, 0x7F, 0, 0, 0, 0, 0, 0, 0};
  const double v = 2.5;
  const auto u = std::bit_cast<uint64_t>(v);
  for (int i = 0; i < 8; ++i) b.push_back(static_cast<uint8_t>(u >> (8 * i)));
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(b, MessageEncoding::kCdr, &error)) << error;
  EXPECT_EQ(r.U8("a"), 0x7F);
  EXPECT_EQ(r.F64("b"), 2.5);
  EXPECT_TRUE(r.Finish());
}

TEST(MessageReader, BigEndianCdr) {
  // u32 at 4, then a float64 aligned to 8 from byte 4: 4 padding bytes, at 12.
  Bytes b(4 + 4 + 4 + 8, 0);
  b[1] = 0x00;  // CDR_BE
  b[4] = 0x12;
  b[5] = 0x34;
  b[6] = 0x56;
  b[7] = 0x78;
  PutF64Be(b, 12, -1.25);
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(b, MessageEncoding::kCdr, &error)) << error;
  EXPECT_EQ(r.U32("a"), 0x12345678u);
  EXPECT_EQ(r.F64("b"), -1.25);
  EXPECT_TRUE(r.Finish());
}

TEST(MessageReader, RefusesXcdr2AndShortHeaders) {
  MessageReader r;
  std::string error;
  EXPECT_FALSE(r.Begin(Bytes{0x00, 0x07, 0x00, 0x00, 1, 2, 3, 4}, MessageEncoding::kCdr, &error));
  EXPECT_NE(error.find("0x0007"), std::string::npos) << error;
  EXPECT_FALSE(r.Begin(Bytes{0x00, 0x01}, MessageEncoding::kCdr, &error));
  EXPECT_FALSE(r.Begin(Bytes{0x00, 0x01, 0, 0}, MessageEncoding::kUnknown, &error));
}

TEST(MessageReader, CdrStringsNeedTheirNul) {
  MessageWriter w(MessageEncoding::kCdr);
  w.String("abc");
  Bytes good = w.Take();
  ASSERT_EQ(good.size(), 4u + 4 + 4);  // header, length 4, "abc\0"
  EXPECT_EQ(good[4], 4);
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(good, MessageEncoding::kCdr, &error));
  EXPECT_EQ(r.String("s"), "abc");
  EXPECT_TRUE(r.Finish());
  Bytes bad = good;
  bad.back() = 'd';  // no NUL: not a CDR string
  ASSERT_TRUE(r.Begin(bad, MessageEncoding::kCdr, &error));
  EXPECT_EQ(r.String("s"), "");
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.Failure().find("impossible"), std::string::npos) << r.Failure();
}

TEST(MessageReader, Ros1HasNoAlignmentNoNulAndASeqInTheHeader) {
  MessageWriter w(MessageEncoding::kRos1);
  w.U8(1);
  w.F64(3.0);  // no padding before it
  w.Header(5'000'000'007, "map");
  const Bytes b = w.Take();
  ASSERT_EQ(b.size(), 1u + 8 + 4 + 8 + 4 + 3);
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(b, MessageEncoding::kRos1, &error));
  EXPECT_EQ(r.U8("a"), 1);
  EXPECT_EQ(r.F64("b"), 3.0);
  const RosHeader h = r.Header();
  EXPECT_EQ(h.stamp_ns, 5'000'000'007);
  EXPECT_EQ(h.frame_id, "map");
  EXPECT_TRUE(r.Finish());
}

TEST(MessageReader, FailureIsStickyAndNamesTheField) {
  MessageWriter w(MessageEncoding::kCdr);
  w.U32(7);
  Bytes b = w.Take();
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(b, MessageEncoding::kCdr, &error));
  EXPECT_EQ(r.U32("first"), 7u);
  EXPECT_EQ(r.F64("second"), 0.0);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.U32("third"), 0u);
  EXPECT_EQ(r.Failure(), "byte 8: second needs 8 bytes, 0 left");
  EXPECT_FALSE(r.Finish());
}

TEST(MessageReader, SequenceCountsAreBoundedByTheBytesLeft) {
  MessageWriter w(MessageEncoding::kCdr);
  w.U32(0xFFFFFFFFu);  // a count no message can hold
  w.U32(0);
  const Bytes b = w.Take();
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(b, MessageEncoding::kCdr, &error));
  EXPECT_EQ(r.SequenceLength("packets", 1256), 0u);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.Failure().find("packets"), std::string::npos);
}

TEST(MessageReader, AllowsUpToThreePaddingBytesInCdrNoneInRos1) {
  for (size_t pad = 0; pad <= 4; ++pad) {
    Bytes b = {0x00, 0x01, 0x00, 0x00, 9};
    b.resize(b.size() + pad, 0);
    MessageReader r;
    std::string error;
    ASSERT_TRUE(r.Begin(b, MessageEncoding::kCdr, &error));
    r.U8("x");
    EXPECT_EQ(r.Finish(), pad <= 3) << pad;
  }
  MessageReader r;
  std::string error;
  const Bytes ros1 = {9, 0};
  ASSERT_TRUE(r.Begin(ros1, MessageEncoding::kRos1, &error));
  r.U8("x");
  EXPECT_FALSE(r.Finish());
}

TEST(MessageReader, TimeRefusesNanosecondsOfASecondOrMore) {
  MessageWriter w(MessageEncoding::kCdr);
  w.U32(1);
  w.U32(1'000'000'000);
  const Bytes b = w.Take();
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(b, MessageEncoding::kCdr, &error));
  r.Time("stamp");
  EXPECT_FALSE(r.ok());
}

TEST(MessageReader, NegativeRos2SecondsAndTheWritersFloorDivision) {
  MessageWriter w(MessageEncoding::kCdr);
  w.Time(-1);  // sec −1, nanosec 999999999
  const Bytes b = w.Take();
  MessageReader r;
  std::string error;
  ASSERT_TRUE(r.Begin(b, MessageEncoding::kCdr, &error));
  EXPECT_EQ(r.Time("t"), -1);
  EXPECT_TRUE(r.Finish());
}

}  // namespace
}  // namespace swlio::drivers::bag

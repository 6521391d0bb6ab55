#include "swlio/drivers/wheel_odom_decoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace swlio::drivers {
namespace {

/// Independent reference encoder: walks the bits the way the DBC documentation draws them
/// (Intel upwards from the LSB; Motorola from the MSB down the "sawtooth": after bit 0 of a
/// byte comes bit 7 of the next byte).
void PutBits(CanFrame& f, int start, int len, bool motorola, uint64_t raw) {
  int pos = start;
  for (int k = 0; k < len; ++k) {
    const int value_bit = motorola ? len - 1 - k : k;
    const auto byte = static_cast<size_t>(pos / 8);
    const auto mask = static_cast<uint8_t>(1u << (pos % 8));
    if (((raw >> value_bit) & 1u) != 0) {
      f.data[byte] = static_cast<uint8_t>(f.data[byte] | mask);
    } else {
      f.data[byte] = static_cast<uint8_t>(f.data[byte] & ~mask);
    }
    if (motorola) {
      pos = (pos % 8 == 0) ? pos + 15 : pos - 1;
    } else {
      ++pos;
    }
  }
}

CanSignalConfig Signal(
    const char* role, int64_t id, int64_t start_bit, int64_t len, const char* order) {
  CanSignalConfig s;
  s.role = role;
  s.can_id = id;
  s.start_bit = start_bit;
  s.length_bits = len;
  s.byte_order = order;
  return s;
}

CanFrame Frame(uint32_t id, std::initializer_list<uint8_t> bytes, bool extended = false) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.dlc = static_cast<uint8_t>(bytes.size());
  size_t i = 0;
  for (uint8_t b : bytes) f.data[i++] = b;
  return f;
}

TEST(CanSignal, HandWorkedExamples) {
  const CanFrame f = Frame(0x100, {0x12, 0x34, 0x56, 0x78, 0x9A, 0xBC, 0xDE, 0xF0});
  auto value = [&](int64_t start, int64_t len, const char* order, bool is_signed) {
    CanSignalConfig c = Signal("linear_velocity", 0x100, start, len, order);
    c.is_signed = is_signed;
    auto s = CompileCanSignal(c);
    EXPECT_TRUE(s.has_value());
    return s ? ExtractCanSignal(*s, f) : NAN;
  };
  EXPECT_EQ(value(0, 16, "intel", false), 0x3412);
  EXPECT_EQ(value(7, 16, "motorola", false), 0x1234);
  EXPECT_EQ(value(3, 12, "motorola", false), 0x234);  // low nibble of byte 0, then byte 1
  EXPECT_EQ(value(4, 8, "intel", false), 0x41);       // high nibble of byte 0, low of byte 1
  EXPECT_EQ(value(56, 8, "intel", true), -16);        // 0xF0
  EXPECT_EQ(value(0, 64, "intel", false), static_cast<double>(0xF0DEBC9A78563412ull));
  EXPECT_EQ(value(63, 8, "motorola", true), -16);  // byte 7, MSB at bit 63
}

TEST(CanSignal, ScaleOffsetAndByteOffset) {
  CanSignalConfig c = Signal("left_wheel_speed", 0x1, -1, 16, "motorola");
  c.byte_offset = 2;
  c.scale = 0.01;
  c.offset = -1.0;
  const auto s = CompileCanSignal(c);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->min_dlc, 4);
  const CanFrame f = Frame(0x1, {0, 0, 0xFF, 0x38});  // 0xFF38 = -200
  EXPECT_DOUBLE_EQ(ExtractCanSignal(*s, f), -200 * 0.01 - 1.0);
}

TEST(CanSignal, RandomLayoutsMatchTheReferenceEncoder) {
  std::mt19937_64 rng(42);
  int checked = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const bool motorola = (rng() & 1u) != 0;
    const int len = static_cast<int>(1 + rng() % 64);
    CanSignalConfig c = Signal("linear_velocity", 0x10, static_cast<int64_t>(rng() % 64), len,
                               motorola ? "motorola" : "intel");
    c.is_signed = (rng() & 1u) != 0;
    auto s = CompileCanSignal(c);
    if (!s) continue;  // field does not fit in 8 bytes: Validate() said so
    const uint64_t mask = len == 64 ? ~0ull : (1ull << len) - 1;
    const uint64_t raw = rng() & mask;
    CanFrame f = Frame(0x10, {});
    f.dlc = 8;
    for (auto& b : f.data) b = static_cast<uint8_t>(rng());  // other bits: noise
    PutBits(f, static_cast<int>(c.start_bit), len, motorola, raw);
    double expected = static_cast<double>(raw);
    if (c.is_signed && len < 64 && ((raw >> (len - 1)) & 1u)) {
      expected = static_cast<double>(static_cast<int64_t>(raw) - static_cast<int64_t>(1ull << len));
    } else if (c.is_signed && len == 64) {
      expected = static_cast<double>(static_cast<int64_t>(raw));
    }
    ASSERT_EQ(ExtractCanSignal(*s, f), expected)
        << "start " << c.start_bit << " len " << len << " motorola " << motorola;
    ++checked;
  }
  EXPECT_GT(checked, 2000);
}

TEST(CanConfigLayout, ReportsEveryProblem) {
  CanConfig c;
  c.enabled = true;
  auto keys = [](const ConfigIssues& issues) {
    std::string all;
    for (const auto& i : issues) all += i.key + ";";
    return all;
  };
  EXPECT_NE(keys(c.Validate()).find("signals;"), std::string::npos);  // none configured
  CanSignalConfig bad = Signal("left_wheel", 0x800, 60, 16, "big");
  bad.byte_offset = 1;
  bad.scale = 0.0;
  c.signals = {bad, Signal("right_wheel_speed", 0x12345, 0, 8, "intel")};
  const std::string k = keys(c.Validate());
  for (const char* key : {"signals[0].role", "signals[0].can_id", "signals[0].byte_order",
                          "signals[0].start_bit", "signals[0].scale", "signals[1].can_id"}) {
    EXPECT_NE(k.find(key), std::string::npos) << key << " missing from " << k;
  }
  CanSignalConfig overflow = Signal("left_wheel_speed", 0x1, 60, 16, "intel");
  EXPECT_FALSE(overflow.Validate().empty());
  CanSignalConfig moto_overflow = Signal("left_wheel_speed", 0x1, 57, 16, "motorola");
  EXPECT_FALSE(moto_overflow.Validate().empty());  // MSB in byte 7 runs past the frame
  CanSignalConfig extended = Signal("left_wheel_speed", 0x12345, 0, 8, "intel");
  extended.extended = true;
  EXPECT_TRUE(extended.Validate().empty());
  CanConfig disabled;
  EXPECT_TRUE(disabled.Validate().empty());  // the default config is valid
}

CanConfig WheelLayout(uint32_t left_id, uint32_t right_id) {
  CanConfig c;
  c.enabled = true;
  c.mode = "wheel_speeds";
  c.track_width_m = 0.5;
  CanSignalConfig left = Signal("left_wheel_speed", left_id, 0, 16, "intel");
  left.scale = 0.001;
  CanSignalConfig right = left;
  right.role = "right_wheel_speed";
  right.can_id = right_id;
  right.start_bit = left_id == right_id ? 16 : 0;
  c.signals = {left, right};
  return c;
}

TEST(WheelOdomDecoder, DifferentialDriveFromOneFrame) {
  auto d = WheelOdomDecoder::Create(WheelLayout(0x201, 0x201));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->NumIds(), 1);
  // left = 1000 mm/s, right = -500 mm/s (0xFE0C).
  const auto s = d->Decode(Frame(0x201, {0xE8, 0x03, 0x0C, 0xFE, 0, 0, 0, 0}), 77);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->t_ns, 77);
  EXPECT_TRUE(s->has_wheel_speeds);
  EXPECT_DOUBLE_EQ(s->left_wheel_mps, 1.0);
  EXPECT_DOUBLE_EQ(s->right_wheel_mps, -0.5);
  EXPECT_DOUBLE_EQ(s->linear_velocity_mps, 0.25);
  EXPECT_DOUBLE_EQ(s->yaw_rate_radps, -3.0);  // (−0.5 − 1.0) / 0.5: turning clockwise
}

TEST(WheelOdomDecoder, RadPerSecondUsesTheWheelRadius) {
  CanConfig c = WheelLayout(0x201, 0x201);
  c.wheel_speed_unit = "radps";
  c.wheel_radius_m = 0.2;
  auto d = WheelOdomDecoder::Create(c);
  ASSERT_TRUE(d);
  const auto s = d->Decode(Frame(0x201, {0xD0, 0x07, 0xB8, 0x0B}), 1);  // 2.0 and 3.0 rad/s
  ASSERT_TRUE(s);
  EXPECT_DOUBLE_EQ(s->left_wheel_mps, 0.4);
  EXPECT_DOUBLE_EQ(s->right_wheel_mps, 0.6);
  EXPECT_DOUBLE_EQ(s->yaw_rate_radps, 0.4);
}

TEST(WheelOdomDecoder, PairsSignalsFromTwoFramesAndDropsStaleOnes) {
  auto d = WheelOdomDecoder::Create(WheelLayout(0x301, 0x302));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->NumIds(), 2);
  EXPECT_FALSE(d->Decode(Frame(0x301, {0x64, 0x00}), 1'000'000));
  const auto s = d->Decode(Frame(0x302, {0xC8, 0x00}), 2'000'000);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->t_ns, 2'000'000);
  EXPECT_DOUBLE_EQ(s->linear_velocity_mps, 0.15);
  // Left twice in a row: the first left value never got a partner.
  EXPECT_FALSE(d->Decode(Frame(0x301, {0x01, 0x00}), 3'000'000));
  EXPECT_FALSE(d->Decode(Frame(0x301, {0x02, 0x00}), 4'000'000));
  EXPECT_EQ(d->counters().unpaired_dropped, 1u);
  // Right arrives 100 ms later than left: beyond max_pair_skew_s (50 ms), no sample.
  EXPECT_FALSE(d->Decode(Frame(0x302, {0x03, 0x00}), 104'000'000));
  EXPECT_EQ(d->counters().unpaired_dropped, 2u);
  const auto late = d->Decode(Frame(0x301, {0x05, 0x00}), 110'000'000);
  ASSERT_TRUE(late);
  EXPECT_DOUBLE_EQ(late->left_wheel_mps, 0.005);
  EXPECT_DOUBLE_EQ(late->right_wheel_mps, 0.003);
  EXPECT_EQ(d->counters().samples, 2u);
}

TEST(WheelOdomDecoder, CountsFramesItCannotUse) {
  CanConfig c = WheelLayout(0x201, 0x201);
  c.signals[0].dlc = 8;
  c.signals[1].dlc = 8;
  auto d = WheelOdomDecoder::Create(c);
  ASSERT_TRUE(d);
  EXPECT_FALSE(d->Decode(Frame(0x202, {1, 2, 3, 4, 5, 6, 7, 8}), 0));        // unknown id
  EXPECT_FALSE(d->Decode(Frame(0x201, {1, 2, 3, 4}), 0));                    // DLC 4 ≠ 8
  EXPECT_FALSE(d->Decode(Frame(0x201, {1, 2, 3, 4, 5, 6, 7, 8}, true), 0));  // extended
  CanFrame remote = Frame(0x201, {});
  remote.remote = true;
  remote.dlc = 8;
  EXPECT_FALSE(d->Decode(remote, 0));
  CanFrame error = Frame(0x201, {0, 0, 0, 0, 0, 0, 0, 0});
  error.error = true;
  EXPECT_FALSE(d->Decode(error, 0));
  CanFrame too_long = Frame(0x201, {});
  too_long.dlc = 15;  // impossible for classic CAN; must not read past data[8]
  EXPECT_FALSE(d->Decode(too_long, 0));
  const auto& n = d->counters();
  EXPECT_EQ(n.frames, 6u);
  EXPECT_EQ(n.unknown_id, 2u);
  EXPECT_EQ(n.bad_dlc, 2u);
  EXPECT_EQ(n.remote_or_error, 2u);
  EXPECT_EQ(n.samples, 0u);
  EXPECT_TRUE(d->Decode(Frame(0x201, {1, 0, 2, 0, 0, 0, 0, 0}), 0));
}

TEST(WheelOdomDecoder, AFrameTooShortForOneSignalIsNotUsedAtAll) {
  auto d = WheelOdomDecoder::Create(WheelLayout(0x201, 0x201));  // needs 2 and 4 bytes
  ASSERT_TRUE(d);
  EXPECT_FALSE(d->Decode(Frame(0x201, {0x10, 0x00}), 1));
  EXPECT_EQ(d->counters().bad_dlc, 1u);
  EXPECT_EQ(d->counters().frames_used, 0u);
  const auto s = d->Decode(Frame(0x201, {0x01, 0x00, 0x02, 0x00}), 2);
  ASSERT_TRUE(s);
  EXPECT_DOUBLE_EQ(s->left_wheel_mps, 0.001);  // not the 0x10 of the short frame
  EXPECT_EQ(d->counters().unpaired_dropped, 0u);
}

TEST(WheelOdomDecoder, TwistModeAndExtendedIds) {
  CanConfig c;
  c.mode = "twist";
  CanSignalConfig v = Signal("linear_velocity", 0x18FF0001, 7, 16, "motorola");
  v.extended = true;
  v.scale = 0.01;
  CanSignalConfig w = Signal("angular_velocity", 0x18FF0001, 23, 16, "motorola");
  w.extended = true;
  w.scale = 0.001;
  c.signals = {w, v};  // order in the list does not matter
  auto d = WheelOdomDecoder::Create(c);
  ASSERT_TRUE(d);
  const auto s = d->Decode(Frame(0x18FF0001, {0x00, 0x96, 0xFF, 0x9C}, true), 5);
  ASSERT_TRUE(s);
  EXPECT_FALSE(s->has_wheel_speeds);
  EXPECT_DOUBLE_EQ(s->linear_velocity_mps, 1.5);
  EXPECT_DOUBLE_EQ(s->yaw_rate_radps, -0.1);
  EXPECT_FALSE(d->Decode(Frame(0x0001, {0x00, 0x96, 0xFF, 0x9C}), 6));  // standard id ≠
}

TEST(WheelOdomDecoder, RejectsIncompleteLayouts) {
  CanConfig c = WheelLayout(0x201, 0x201);
  c.signals[1].role = "left_wheel_speed";
  ConfigIssues issues;
  EXPECT_FALSE(WheelOdomDecoder::Create(c, &issues));
  EXPECT_FALSE(issues.empty());
  c = WheelLayout(0x201, 0x201);
  c.mode = "twist";
  EXPECT_FALSE(WheelOdomDecoder::Create(c));
}

}  // namespace
}  // namespace swlio::drivers

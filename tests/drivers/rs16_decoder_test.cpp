#include "swlio/drivers/rs16_decoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "swlio/drivers/bytes.h"
#include "swlio/drivers/rs16_encoder.h"

namespace swlio::drivers {
namespace {

using Packet = std::vector<uint8_t>;
constexpr double kPi = 3.14159265358979323846;
// 2017-01-01 00:03:19.402130 UTC (the real capture's first packet) in ns since 1970.
constexpr int64_t kT0 = (1483228800LL + 199) * 1'000'000'000LL + 402'130'000LL;

LidarConfig OpenRangeConfig() {
  LidarConfig c;
  c.min_range_m = 0.0;
  c.max_range_m = 400.0;
  return c;
}

Rs16MsopContent UniformContent(double az0_deg, double step_deg, float range_m) {
  Rs16MsopContent c;
  c.t_sensor_ns = kT0;
  for (size_t b = 0; b < 12; ++b) {
    c.blocks[b].azimuth_deg = az0_deg + step_deg * static_cast<double>(b);
    c.blocks[b].range_m.fill(range_m);
    c.blocks[b].intensity.fill(static_cast<uint8_t>(b));
  }
  return c;
}

Packet Encode(const Rs16MsopContent& c) {
  Packet p(1248);
  EXPECT_TRUE(EncodeRs16Msop(c, p));
  return p;
}

struct Decoded {
  DecodeStatus status;
  LidarPacketSummary summary;
  std::vector<LidarReturn> returns;
};

Decoded Decode(const Rs16Decoder& d, const Packet& p) {
  LidarPacketDecoder::ReturnBuffer buf;
  Decoded out;
  out.status = d.DecodeData(p, buf, &out.summary);
  if (out.status == DecodeStatus::kOk) {
    out.returns.assign(buf.begin(), buf.begin() + out.summary.returns);
  }
  return out;
}

TEST(Rs16Decoder, ClassifiesByLengthAndId) {
  Rs16Decoder d(LidarConfig{});
  Packet msop = Encode(UniformContent(0, 0.4, 5));
  Packet difop(1248);
  ASSERT_TRUE(EncodeRs16Difop({}, difop));
  EXPECT_EQ(d.Classify(msop), LidarPacketKind::kData);
  EXPECT_EQ(d.Classify(difop), LidarPacketKind::kInfo);
  msop.pop_back();
  EXPECT_EQ(d.Classify(msop), LidarPacketKind::kUnknown);
  EXPECT_EQ(d.Classify(Packet(1248, 0)), LidarPacketKind::kUnknown);
}

TEST(Rs16Decoder, RejectsMalformedPackets) {
  Rs16Decoder d(OpenRangeConfig());
  const Packet good = Encode(UniformContent(10, 0.4, 5));
  EXPECT_EQ(Decode(d, good).status, DecodeStatus::kOk);
  EXPECT_EQ(Decode(d, Packet(good.begin(), good.end() - 1)).status, DecodeStatus::kWrongSize);
  Packet bad = good;
  bad[3] ^= 1;
  EXPECT_EQ(Decode(d, bad).status, DecodeStatus::kBadHeader);
  bad = good;
  bad[42 + 5 * 100 + 1] = 0xEF;  // block 5 flag
  EXPECT_EQ(Decode(d, bad).status, DecodeStatus::kBadHeader);
  bad = good;
  bytes::WriteU16Be(&bad[42 + 7 * 100 + 2], 36000);  // azimuth ≥ 360°
  EXPECT_EQ(Decode(d, bad).status, DecodeStatus::kBadHeader);
  bad = good;
  bad[21] = 13;  // month 13
  EXPECT_EQ(Decode(d, bad).status, DecodeStatus::kBadHeader);
  LidarPacketSummary s;
  std::vector<LidarReturn> small(100);
  EXPECT_EQ(d.DecodeData(good, small, &s), DecodeStatus::kBufferTooSmall);
}

TEST(Rs16Decoder, NoReturnCodesAndRangeLimitsAreCounted) {
  LidarConfig config;  // min 0.4 m, max 150 m
  Rs16Decoder d(config);
  Rs16MsopContent c = UniformContent(0, 0.4, 5);
  c.blocks[0].range_m[0] = 0.0f;    // code 0
  c.blocks[0].range_m[1] = 0.3f;    // below min_range_m
  c.blocks[0].range_m[2] = 200.0f;  // beyond max_range_m
  Packet p = Encode(c);
  bytes::WriteU16Be(&p[42 + 4 + 3 * 3], 0xFFFF);  // slot 3: code 0xFFFF
  const Decoded r = Decode(d, p);
  ASSERT_EQ(r.status, DecodeStatus::kOk);
  EXPECT_EQ(r.summary.returns, 384u - 4u);
  EXPECT_EQ(r.summary.no_returns, 4u);
  EXPECT_EQ(r.returns[0].slot, 4);
}

// rs_driver's frame (x forward at azimuth 0, y left, z up) with its lens offset RX = 3.825 cm
// along the firing azimuth, by default.
TEST(Rs16Decoder, GeometryFollowsTheVendorFrame) {
  Rs16Decoder d(OpenRangeConfig());  // nominal angles: channel 0 −15°, channel 8 +15°
  Rs16MsopContent c = UniformContent(90.0, 0.0, 0.0f);
  c.blocks[0].range_m[0] = 10.0f;  // laser 0, first firing at exactly the block azimuth
  c.blocks[0].range_m[8] = 10.0f;
  c.blocks[1].azimuth_deg = 90.0;  // zero step: no interpolation
  for (size_t b = 2; b < 12; ++b) c.blocks[b].azimuth_deg = 0.0;
  c.blocks[2].range_m[0] = 10.0f;  // laser 0 at azimuth 0
  const Decoded r = Decode(d, Encode(c));
  ASSERT_EQ(r.returns.size(), 3u);
  const double cos15 = std::cos(15.0 * kPi / 180), sin15 = std::sin(15.0 * kPi / 180);
  const double lens = 0.03825;
  EXPECT_NEAR(r.returns[0].x_m, 0.0, 1e-5);  // azimuth 90° (clockwise): −y, to the right
  EXPECT_NEAR(r.returns[0].y_m, -(10 * cos15 + lens), 1e-5);
  EXPECT_NEAR(r.returns[0].z_m, -10 * sin15, 1e-5);
  EXPECT_EQ(r.returns[0].ring, 0);
  EXPECT_NEAR(r.returns[1].z_m, 10 * sin15, 1e-5);
  EXPECT_EQ(r.returns[1].ring, 15);  // channel 8 points highest
  EXPECT_FLOAT_EQ(r.returns[0].azimuth_deg, 90.0f);
  EXPECT_NEAR(r.returns[2].x_m, 10 * cos15 + lens, 1e-5);  // azimuth 0: +x, forward
  EXPECT_NEAR(r.returns[2].y_m, 0.0, 1e-5);
  EXPECT_FLOAT_EQ(r.returns[2].azimuth_deg, 0.0f);
}

TEST(Rs16Decoder, FiringTimesAndAzimuthInterpolationSingleReturn) {
  Rs16Decoder d(OpenRangeConfig());
  const Decoded r = Decode(d, Encode(UniformContent(100.0, 0.4, 5.0f)));
  ASSERT_EQ(r.returns.size(), 384u);
  EXPECT_EQ(r.summary.t_sensor_ns, kT0);
  EXPECT_FLOAT_EQ(r.summary.first_azimuth_deg, 100.0f);
  EXPECT_NEAR(r.summary.last_azimuth_deg, 104.4f, 1e-4);
  for (const LidarReturn& ret : r.returns) {
    const int b = ret.slot / 32, s = ret.slot % 32;
    const int offset = (s % 16) * 2800 + (s / 16) * 55500;
    EXPECT_EQ(ret.t_sensor_ns, kT0 + int64_t{b} * 111000 + offset) << ret.slot;
    // 0.4° per 111 µs block; the last block continues with the previous step.
    EXPECT_NEAR(ret.azimuth_deg, 100.0 + 0.4 * b + 0.4 * offset / 111000.0, 2e-4) << ret.slot;
    EXPECT_NEAR(ret.range_m, 5.0, 1e-6);
    EXPECT_EQ(ret.return_index, 0);
  }
  EXPECT_NEAR(d.PacketsPerRevolution(), 1e8 / (12 * 111000.0), 1e-9);
}

TEST(Rs16Decoder, AzimuthWrapsAndJumpsUseNominalStep) {
  Rs16Decoder d(OpenRangeConfig());
  Rs16MsopContent c = UniformContent(359.0, 0.4, 5.0f);  // crosses 360 at block 3
  c.blocks[6].azimuth_deg = 200.0;                       // a jump: nominal step instead
  const Decoded r = Decode(d, Encode(c));
  ASSERT_EQ(r.status, DecodeStatus::kOk);
  for (const LidarReturn& ret : r.returns) {
    EXPECT_GE(ret.azimuth_deg, 0.0f);
    EXPECT_LT(ret.azimuth_deg, 360.0f);
  }
  const LidarReturn& wrapped = r.returns[3 * 32 + 16];  // block 3, second firing
  EXPECT_NEAR(wrapped.azimuth_deg, 0.2 + 0.2, 2e-3);    // 360.2 → 0.2, + half a step
  const LidarReturn& jumped = r.returns[5 * 32 + 16];   // block 5 → 6 step is bogus
  EXPECT_NEAR(jumped.azimuth_deg, 1.0 + 0.5 * 0.3996, 2e-3);
}

TEST(Rs16Decoder, DifopSetsDualModeCalibrationRpmAndPorts) {
  // An unusual channel order, configured as such (the configuration is by ring in the nominal
  // channel order), so that the DIFOP's calibration (0.05° off it) is plausible.
  const std::array<double, 16> by_channel = {-1, -3, -5, -7, -9, -11, -13, -15,
                                             2,  4,  6,  8,  10, 12,  14,  0};
  LidarConfig config = OpenRangeConfig();
  for (size_t c = 0; c < 16; ++c)
    config.vertical_angles_deg[rs16::kNominalRingOfChannel[c]] = by_channel[c];
  Rs16Decoder d(config);
  Rs16DifopContent info;
  info.rpm = 1200;
  info.msop_port = 2244;
  info.difop_port = 7788;
  info.return_mode = ReturnMode::kDual;
  for (size_t c = 0; c < 16; ++c)
    info.vertical_angles_deg[c] = by_channel[c] + (c < 8 ? -0.05 : 0.05);
  Packet difop(1248);
  ASSERT_TRUE(EncodeRs16Difop(info, difop));
  ASSERT_EQ(d.DecodeInfo(difop), DecodeStatus::kOk);
  EXPECT_NEAR(d.vertical_deg_by_channel()[0], -1.05, 1e-9);
  EXPECT_EQ(d.Rpm(), 1200.0);
  EXPECT_EQ(d.return_mode(), ReturnMode::kDual);
  EXPECT_EQ(d.difop().msop_dst_port, 2244);
  EXPECT_EQ(d.difop().difop_dst_port, 7788);
  EXPECT_EQ(d.BlockPeriodNs(), 55500);
  const std::array<uint16_t, 16> rings = {7, 6, 5, 4, 3, 2, 1, 0, 9, 10, 11, 12, 13, 14, 15, 8};
  EXPECT_EQ(d.ring_of_channel(), rings);  // −15° (channel 7) lowest, +14° (channel 14) highest
  const Decoded r = Decode(d, Encode(UniformContent(10.0, 0.4, 5.0f)));
  ASSERT_EQ(r.returns.size(), 384u);
  const LidarReturn& first = r.returns[32 + 3];
  const LidarReturn& second = r.returns[32 + 16 + 3];
  EXPECT_EQ(first.return_index, 0);
  EXPECT_EQ(second.return_index, 1);
  EXPECT_EQ(first.t_sensor_ns, second.t_sensor_ns);
  EXPECT_EQ(first.t_sensor_ns, kT0 + 55500 + int64_t{3} * 2800);
  EXPECT_NEAR(first.azimuth_deg, 10.4 + 0.4 * 3 * 2800 / 55500.0, 2e-4);
  EXPECT_NEAR(d.PacketsPerRevolution(), 5e7 / (12 * 55500.0), 1e-9);
}

TEST(Rs16Decoder, BlankDifopCalibrationKeepsConfigAngles) {
  LidarConfig config = OpenRangeConfig();
  Rs16Decoder d(config);
  Packet difop(1248);
  ASSERT_TRUE(EncodeRs16Difop({}, difop));
  std::fill(difop.begin() + 1165, difop.begin() + 1165 + 48, uint8_t{0xFF});
  bytes::WriteU16Be(&difop[8], 0);  // rpm 0: keep the configured speed
  ASSERT_EQ(d.DecodeInfo(difop), DecodeStatus::kOk);
  EXPECT_FALSE(d.difop().has_vertical_calibration);
  EXPECT_EQ(d.Rpm(), 600.0);
  EXPECT_EQ(d.vertical_deg_by_channel()[8], 15.0);
  EXPECT_EQ(d.vertical_deg_by_channel()[15], 1.0);
  difop[0] = 0;
  EXPECT_EQ(d.DecodeInfo(difop), DecodeStatus::kBadHeader);
}

// One flipped bit (2^14 · 0.0001° = 1.64°) in a calibration angle: the DIFOP is damaged, and
// nothing of it (not even its rpm) is adopted.
TEST(Rs16Decoder, DamagedDifopCalibrationIsRefused) {
  Rs16Decoder d(OpenRangeConfig());
  Rs16DifopContent info;
  info.rpm = 1200;
  info.vertical_angles_deg[3] -= 0.03;  // a factory calibration: adopted
  Packet difop(1248);
  ASSERT_TRUE(EncodeRs16Difop(info, difop));
  ASSERT_EQ(d.DecodeInfo(difop), DecodeStatus::kOk);
  EXPECT_NEAR(d.vertical_deg_by_channel()[3], -9.03, 1e-9);
  info.rpm = 300;
  Packet damaged(1248);
  ASSERT_TRUE(EncodeRs16Difop(info, damaged));
  damaged[rs16::kDifopPitchCali + 3 * 3 + 1] ^= 0x40;  // bit 14 of channel 3's magnitude
  EXPECT_EQ(d.DecodeInfo(damaged), DecodeStatus::kImplausible);
  EXPECT_EQ(d.Rpm(), 1200.0);
  EXPECT_NEAR(d.vertical_deg_by_channel()[3], -9.03, 1e-9);
}

// The range term follows the calibrated azimuth, the lens term the uncalibrated one
// (rs_driver decoder_RS16.hpp L316–318); a lens offset of 0 gives the manual's formula.
TEST(Rs16Decoder, LensOffsetAlongTheFiringAzimuth) {
  for (const double lens : {0.03825, 0.0, 0.05}) {
    SCOPED_TRACE(lens);
    Rs16DecoderOptions options;
    options.lens_offset_m = lens;
    Rs16Decoder d(OpenRangeConfig(), options);
    std::array<double, 16> horizontal{};
    horizontal[0] = 1.0;
    d.SetCalibration(d.vertical_deg_by_channel(), horizontal);
    Rs16MsopContent c = UniformContent(30.0, 0.0, 0.0f);
    c.blocks[0].range_m[0] = 10.0f;
    const Decoded r = Decode(d, Encode(c));
    ASSERT_EQ(r.returns.size(), 1u);
    const double rxy = 10.0 * std::cos(15.0 * kPi / 180);
    const double a = 30.0 * kPi / 180, af = 31.0 * kPi / 180;
    EXPECT_NEAR(r.returns[0].x_m, rxy * std::cos(af) + lens * std::cos(a), 1e-5);
    EXPECT_NEAR(r.returns[0].y_m, -rxy * std::sin(af) - lens * std::sin(a), 1e-5);
    EXPECT_FLOAT_EQ(r.returns[0].range_m, 10.0f);
  }
  EXPECT_EQ(Rs16DecoderOptions{}.lens_offset_m, 0.03825);  // rs_driver's RX by default
}

TEST(Rs16Decoder, OldFirmwareDistanceResolutionAndSingleReturn) {
  Rs16Decoder d(OpenRangeConfig());
  Rs16DifopContent info;
  info.top_firmware = {0x00, 0xFF, 0xFF, 0xFF, 0x00};     // 10 mm per code (ros_rslidar)
  info.bottom_firmware = {0x08, 0x02, 0x08, 0x00, 0x00};  // < 08 02 09: no dual return
  info.return_mode = ReturnMode::kDual;
  Packet difop(1248);
  ASSERT_TRUE(EncodeRs16Difop(info, difop));
  ASSERT_EQ(d.DecodeInfo(difop), DecodeStatus::kOk);
  EXPECT_FALSE(d.difop().supports_dual_return);
  EXPECT_EQ(d.return_mode(), ReturnMode::kStrongest);
  EXPECT_EQ(d.distance_resolution_m(), 0.01);
  Rs16MsopContent c = UniformContent(0.0, 0.4, 12.34f);
  c.distance_resolution_m = 0.01;
  const Decoded r = Decode(d, Encode(c));
  ASSERT_EQ(r.returns.size(), 384u);
  EXPECT_NEAR(r.returns[7].range_m, 12.34, 0.005 + 1e-6);

  Rs16DecoderOptions fixed;
  fixed.distance_resolution_m = 0.005;  // configured: the DIFOP does not override it
  Rs16Decoder f(OpenRangeConfig(), fixed);
  ASSERT_EQ(f.DecodeInfo(difop), DecodeStatus::kOk);
  EXPECT_EQ(f.distance_resolution_m(), 0.005);
}

TEST(Rs16Decoder, HorizontalCalibrationRotatesAzimuth) {
  Rs16DecoderOptions no_lens;
  no_lens.lens_offset_m = 0.0;
  Rs16Decoder d(OpenRangeConfig(), no_lens);
  std::array<double, 16> horizontal{};
  horizontal[2] = -0.5;
  d.SetCalibration(d.vertical_deg_by_channel(), horizontal);
  Rs16MsopContent c = UniformContent(0.2, 0.0, 0.0f);
  c.blocks[0].range_m[2] = 20.0f;
  const Decoded r = Decode(d, Encode(c));
  ASSERT_EQ(r.returns.size(), 1u);
  EXPECT_NEAR(r.returns[0].azimuth_deg, 359.7, 1e-4);
  const double rxy = std::hypot(r.returns[0].x_m, r.returns[0].y_m);
  EXPECT_NEAR(r.returns[0].y_m, -rxy * std::sin(-0.3 * kPi / 180), 1e-5);
  EXPECT_GT(r.returns[0].y_m, 0.0f);  // 0.3° anticlockwise of forward: to the left
}

TEST(Rs16Time, BothHeaderFormats) {
  uint8_t ymd[10] = {0x11, 0x01, 0x01, 0x00, 0x03, 0x13, 0x01, 0x92, 0x00, 0x82};
  int64_t t = 0;
  ASSERT_TRUE(rs16::ParseTime(ymd, rs16::TimeFormat::kAuto, &t));
  EXPECT_EQ(t, kT0);
  ymd[1] |= 0xF0;  // reserved bits above set_month[3:0] (User Manual B.10) are ignored
  ASSERT_TRUE(rs16::ParseTime(ymd, rs16::TimeFormat::kYmd, &t));
  EXPECT_EQ(t, kT0);
  uint8_t utc[10] = {};
  bytes::WriteUBe(utc, 1'700'000'000, 6);
  bytes::WriteU32Be(utc + 6, 999'999);
  ASSERT_TRUE(rs16::ParseTime(utc, rs16::TimeFormat::kAuto, &t));
  EXPECT_EQ(t, 1'700'000'000'999'999'000);
  bytes::WriteU32Be(utc + 6, 1'000'000);
  EXPECT_FALSE(rs16::ParseTime(utc, rs16::TimeFormat::kUtc, &t));
  for (const auto format : {rs16::TimeFormat::kYmd, rs16::TimeFormat::kUtc}) {
    uint8_t buf[10] = {};
    const int64_t when = 1'709'251'199'123'456'789;  // 2024-02-29 23:59:59.123456789
    ASSERT_TRUE(rs16::WriteTime(buf, format, when));
    ASSERT_TRUE(rs16::ParseTime(buf, format, &t));
    EXPECT_EQ(t, when - 789);
  }
  uint8_t buf[10] = {};
  EXPECT_FALSE(rs16::WriteTime(buf, rs16::TimeFormat::kYmd, 0));  // 1970: before 2000
}

TEST(Rs16Encoder, RoundTripWithinQuantization) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> range(0.5f, 120.0f);
  std::uniform_int_distribution<int> inten(0, 255);
  Rs16Decoder d(OpenRangeConfig());
  for (int trial = 0; trial < 20; ++trial) {
    Rs16MsopContent c = UniformContent(trial * 17.3, 0.4, 0.0f);
    c.t_sensor_ns = kT0 + int64_t{trial} * 1'333'000 + 789;
    c.time_format = trial % 2 ? rs16::TimeFormat::kUtc : rs16::TimeFormat::kYmd;
    for (auto& b : c.blocks) {
      for (size_t s = 0; s < 32; ++s) {
        b.range_m[s] = range(rng);
        b.intensity[s] = static_cast<uint8_t>(inten(rng));
      }
    }
    const Decoded r = Decode(d, Encode(c));
    ASSERT_EQ(r.returns.size(), 384u);
    EXPECT_EQ(r.summary.t_sensor_ns, c.t_sensor_ns - 789);
    for (const LidarReturn& ret : r.returns) {
      const auto& b = c.blocks[ret.slot / 32];
      EXPECT_NEAR(ret.range_m, b.range_m[ret.slot % 32], 0.0025 + 1e-5);
      EXPECT_EQ(ret.intensity, b.intensity[ret.slot % 32]);
      EXPECT_NEAR(RangeOfPoint(ret.x_m, ret.y_m, ret.z_m, ret.azimuth_deg), ret.range_m, 1e-4);
    }
    // Re-encoding the decoded returns reproduces the packet's slots bit for bit.
    Rs16MsopContent again = UniformContent(0, 0.4, 0.0f);
    for (size_t b = 0; b < 12; ++b) again.blocks[b].azimuth_deg = c.blocks[b].azimuth_deg;
    again.t_sensor_ns = c.t_sensor_ns;
    again.time_format = c.time_format;
    EXPECT_EQ(FillRs16Slots(r.returns, &again), 384u);
    EXPECT_EQ(Encode(again), Encode(c));
  }
}

TEST(Rs16Encoder, DifopRoundTrip) {
  Rs16DifopContent info;
  info.vertical_angles_deg = {-15.0094, -13.0038, -10.9997, -9.003,  -7.0016, -5.0006,
                              -2.9874,  -1.0026,  14.9994,  13.0038, 10.9997, 9.003,
                              6.998,    5.0006,   2.9946,   1.0026};
  info.t_sensor_ns = kT0;
  Packet p(1248);
  ASSERT_TRUE(EncodeRs16Difop(info, p));
  Rs16DifopInfo parsed;
  ASSERT_EQ(ParseRs16Difop(p, &parsed), DecodeStatus::kOk);
  EXPECT_TRUE(parsed.has_vertical_calibration);
  for (size_t i = 0; i < 16; ++i) {
    EXPECT_NEAR(parsed.vertical_angles_deg[i], info.vertical_angles_deg[i], 1e-9);
  }
  EXPECT_EQ(parsed.rpm, 600.0);
  EXPECT_EQ(parsed.lidar_ip, info.lidar_ip);
  EXPECT_EQ(parsed.return_mode, ReturnMode::kStrongest);
  EXPECT_TRUE(parsed.time_valid);
  EXPECT_EQ(parsed.t_sensor_ns, kT0);
  info.vertical_angles_deg[3] = 2.0;  // positive angle on a downward channel: not encodable
  EXPECT_FALSE(EncodeRs16Difop(info, p));
}

}  // namespace
}  // namespace swlio::drivers

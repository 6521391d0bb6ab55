// The real RS-LiDAR-16 capture (shared/data/rs16_washing_house): decoder, encoder and scan
// assembler checked against counts computed here from the raw bytes by separate simple loops.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/rs16_encoder.h"
#include "swlio/drivers/scan_assembler.h"
#include "test_data.h"

namespace swlio::drivers {
namespace {

using Packet = std::vector<uint8_t>;
constexpr char kCapture[] = "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap";

struct Capture {
  std::vector<Packet> msop;
  std::vector<Packet> difop;
};

Capture Load(const std::filesystem::path& path) {
  Capture c;
  std::string error;
  auto reader = PcapReader::Open(path.string(), {}, &error);
  EXPECT_NE(reader, nullptr) << error;
  UdpDatagram d;
  while (reader && reader->Next(&d)) {
    if (d.dst_port == 2244) c.msop.emplace_back(d.payload.begin(), d.payload.end());
    if (d.dst_port == 7788) c.difop.emplace_back(d.payload.begin(), d.payload.end());
  }
  return c;
}

int U16(const Packet& p, size_t at) { return (p[at] << 8) | p[at + 1]; }

// Independent reference: per-laser counts of distance codes other than 0 and 0xFFFF.
std::array<uint64_t, 16> RawValidPerLaser(const std::vector<Packet>& msop) {
  std::array<uint64_t, 16> n{};
  for (const Packet& p : msop) {
    for (size_t b = 0; b < 12; ++b) {
      for (size_t s = 0; s < 32; ++s) {
        const int code = U16(p, 42 + b * 100 + 4 + s * 3);
        if (code != 0 && code != 0xFFFF) ++n[s % 16];
      }
    }
  }
  return n;
}

// Independent reference: vertical angles from pitch_cali (1165, 16 × 3 bytes, 0.0001°,
// channels 0–7 negative) and the ring of each laser by sorting them.
std::array<double, 16> RawVerticalAngles(const Packet& difop) {
  std::array<double, 16> a{};
  for (size_t i = 0; i < 16; ++i) {
    const size_t at = 1165 + 3 * i;
    const double v = ((difop[at] << 16) | (difop[at + 1] << 8) | difop[at + 2]) * 1e-4;
    a[i] = i < 8 ? -v : v;
  }
  return a;
}

LidarConfig AllRanges() {
  LidarConfig c;
  c.msop_port = 2244;
  c.min_range_m = 0.0;
  c.max_range_m = 400.0;
  return c;
}

TEST(Rs16RealCapture, DifopFields) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  const Capture cap = Load(path);
  ASSERT_EQ(cap.difop.size(), 40u);
  Rs16Decoder decoder(AllRanges());
  for (const Packet& p : cap.difop) ASSERT_EQ(decoder.DecodeInfo(p), DecodeStatus::kOk);
  const Rs16DifopInfo& info = decoder.difop();
  EXPECT_EQ(info.rpm, 600.0);
  EXPECT_EQ(info.msop_dst_port, 2244);
  EXPECT_EQ(info.difop_dst_port, 7788);
  EXPECT_EQ(info.lidar_ip, (std::array<uint8_t, 4>{192, 168, 1, 200}));
  EXPECT_EQ(info.host_ip, (std::array<uint8_t, 4>{192, 168, 1, 102}));
  EXPECT_EQ(info.mac, (std::array<uint8_t, 6>{0x40, 0x2C, 0x76, 0x8C, 0x6F, 0x28}));
  EXPECT_EQ(info.return_mode, ReturnMode::kStrongest);
  // Firmware bytes 40–49 as sent; this unit counts 5 mm per code (its ranges, README: median
  // 3.10 m, max 43.8 m at 5 mm, confirm it) and can do dual return.
  const Packet& raw_difop = cap.difop.front();
  EXPECT_TRUE(std::equal(info.top_firmware.begin(), info.top_firmware.end(), &raw_difop[40]));
  EXPECT_TRUE(std::equal(info.bottom_firmware.begin(), info.bottom_firmware.end(), &raw_difop[45]));
  EXPECT_EQ(info.distance_resolution_m, 0.005);
  EXPECT_TRUE(info.supports_dual_return);
  ASSERT_TRUE(info.has_vertical_calibration);
  const auto raw = RawVerticalAngles(cap.difop.back());
  for (size_t i = 0; i < 16; ++i) EXPECT_DOUBLE_EQ(info.vertical_angles_deg[i], raw[i]) << i;
  EXPECT_NEAR(info.vertical_angles_deg[0], -15.0094, 1e-9);  // spot checks against the bytes
  EXPECT_NEAR(info.vertical_angles_deg[8], 14.9994, 1e-9);
  EXPECT_TRUE(info.time_valid);
  EXPECT_DOUBLE_EQ(decoder.PacketsPerRevolution(), 1e8 / (12 * 111e3));
}

TEST(Rs16RealCapture, DecodesEveryPacketAndCountsMatchTheRawBytes) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  const Capture cap = Load(path);
  ASSERT_EQ(cap.msop.size(), 3000u);
  Rs16Decoder decoder(AllRanges());
  ASSERT_EQ(decoder.DecodeInfo(cap.difop.front()), DecodeStatus::kOk);

  // Ring of each laser, independently: rank of its raw vertical angle.
  const auto angles = RawVerticalAngles(cap.difop.front());
  std::array<size_t, 16> order{};
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return angles[a] < angles[b]; });
  const auto per_laser = RawValidPerLaser(cap.msop);
  std::array<uint64_t, 16> expected_per_ring{};
  for (size_t rank = 0; rank < 16; ++rank) expected_per_ring[rank] = per_laser[order[rank]];
  const uint64_t expected_total = std::accumulate(per_laser.begin(), per_laser.end(), uint64_t{0});
  EXPECT_EQ(expected_total, 1'063'236u);  // the README's figure, from its own parse

  std::array<uint64_t, 16> per_ring{};
  uint64_t total = 0, no_returns = 0;
  LidarPacketDecoder::ReturnBuffer buf;
  int64_t previous_t = 0;
  for (const Packet& p : cap.msop) {
    LidarPacketSummary s;
    ASSERT_EQ(decoder.DecodeData(p, buf, &s), DecodeStatus::kOk);
    total += s.returns;
    no_returns += s.no_returns;
    EXPECT_GT(s.t_sensor_ns, previous_t);
    previous_t = s.t_sensor_ns;
    for (uint32_t i = 0; i < s.returns; ++i) {
      ++per_ring[buf[i].ring];
      ASSERT_GE(buf[i].azimuth_deg, 0.0f);
      ASSERT_LT(buf[i].azimuth_deg, 360.0f);
      ASSERT_LT(buf[i].range_m, 45.0f);  // README: max 43.8 m
    }
  }
  EXPECT_EQ(total, expected_total);
  EXPECT_EQ(total + no_returns, 3000u * 384u);
  EXPECT_EQ(per_ring, expected_per_ring);
}

TEST(Rs16RealCapture, HeaderTimeIsTheLidarClock) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  const Capture cap = Load(path);
  Rs16Decoder decoder(AllRanges());
  LidarPacketDecoder::ReturnBuffer buf;
  LidarPacketSummary first, last;
  ASSERT_EQ(decoder.DecodeData(cap.msop.front(), buf, &first), DecodeStatus::kOk);
  ASSERT_EQ(decoder.DecodeData(cap.msop.back(), buf, &last), DecodeStatus::kOk);
  // README: 2017-01-01 00:03:19.402130 → 00:03:23.400553 (YMD format).
  const int64_t t0 = (1'483'228'800LL + 3LL * 60 + 19) * 1'000'000'000LL + 402'130'000LL;
  EXPECT_EQ(first.t_sensor_ns, t0);
  EXPECT_EQ(last.t_sensor_ns - first.t_sensor_ns, 3'998'423'000);
}

TEST(Rs16RealCapture, ScansFollowTheCutAngleWithoutFalseGaps) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  const Capture cap = Load(path);
  for (const double cut_deg : {0.0, 180.0}) {
    // Independent: block-azimuth crossings of the cut in the raw bytes.
    int crossings = 0;
    int previous = -1;
    for (const Packet& p : cap.msop) {
      for (size_t b = 0; b < 12; ++b) {
        const int rel =
            (U16(p, 42 + b * 100 + 2) - static_cast<int>(cut_deg * 100) + 36000) % 36000;
        if (previous >= 0 && rel < previous - 18000) ++crossings;
        previous = rel;
      }
    }
    Rs16Decoder decoder(AllRanges());
    ASSERT_EQ(decoder.DecodeInfo(cap.difop.front()), DecodeStatus::kOk);
    ScanAssemblerConfig config;
    config.cut_angle_deg = cut_deg;
    config.packets_per_revolution = decoder.PacketsPerRevolution();
    config.revolution_period_ns = static_cast<int64_t>(60e9 / decoder.Rpm());
    ScanAssembler assembler(config);
    LidarPacketDecoder::ReturnBuffer buf;
    std::vector<AssembledScan> scans;
    AssembledScan out;
    uint64_t points = 0;
    for (const Packet& p : cap.msop) {
      LidarPacketSummary s;
      ASSERT_EQ(decoder.DecodeData(p, buf, &s), DecodeStatus::kOk);
      assembler.AddPacket(std::span(buf.data(), s.returns), s);
      while (assembler.PopScan(&out)) scans.push_back(out);
    }
    assembler.Flush();
    while (assembler.PopScan(&out)) scans.push_back(out);

    EXPECT_EQ(assembler.stats().gaps, 0u) << cut_deg;
    EXPECT_EQ(assembler.stats().discontinuities, 0u);
    ASSERT_EQ(scans.size(), static_cast<size_t>(crossings + 1)) << cut_deg;
    EXPECT_TRUE(scans.front().scan.partial);
    EXPECT_TRUE(scans.back().scan.partial);
    for (size_t i = 0; i < scans.size(); ++i) {
      const AssembledScan& s = scans[i];
      points += s.scan.points.size();
      if (i == 0 || i + 1 == scans.size()) continue;
      EXPECT_FALSE(s.scan.partial) << i;
      const double first_rel = std::fmod(s.first_azimuth_deg - cut_deg + 360.0, 360.0);
      const double last_rel = std::fmod(s.last_azimuth_deg - cut_deg + 360.0, 360.0);
      EXPECT_LT(first_rel, 1.0) << i;
      EXPECT_GT(last_rel, 359.0) << i;
      EXPECT_NEAR(static_cast<double>(s.scan.t_end_ns - s.scan.t_start_ns), 1e8, 5e5) << i;
    }
    EXPECT_EQ(points, 1'063'236u);
  }
}

TEST(Rs16RealCapture, ReencodedPacketsDecodeToTheSameReturns) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  const Capture cap = Load(path);
  Rs16Decoder decoder(AllRanges());
  ASSERT_EQ(decoder.DecodeInfo(cap.difop.front()), DecodeStatus::kOk);
  LidarPacketDecoder::ReturnBuffer a, b;
  for (size_t k = 0; k < cap.msop.size(); k += 97) {
    LidarPacketSummary sa, sb;
    ASSERT_EQ(decoder.DecodeData(cap.msop[k], a, &sa), DecodeStatus::kOk);
    Rs16MsopContent content;
    content.t_sensor_ns = sa.t_sensor_ns;
    for (size_t blk = 0; blk < 12; ++blk) {
      content.blocks[blk].azimuth_deg = U16(cap.msop[k], 42 + blk * 100 + 2) * 0.01;
    }
    ASSERT_EQ(FillRs16Slots(std::span(a.data(), sa.returns), &content), sa.returns);
    Packet again(1248);
    ASSERT_TRUE(EncodeRs16Msop(content, again));
    ASSERT_EQ(decoder.DecodeData(again, b, &sb), DecodeStatus::kOk);
    ASSERT_EQ(sb.returns, sa.returns);
    for (uint32_t i = 0; i < sa.returns; ++i) {
      EXPECT_EQ(a[i].slot, b[i].slot);
      EXPECT_EQ(a[i].x_m, b[i].x_m);
      EXPECT_EQ(a[i].intensity, b[i].intensity);
      EXPECT_EQ(a[i].t_sensor_ns, b[i].t_sensor_ns);
    }
  }
}

}  // namespace
}  // namespace swlio::drivers

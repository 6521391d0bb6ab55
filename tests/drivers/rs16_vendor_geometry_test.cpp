// The real RS-LiDAR-16 capture (shared/data/rs16_washing_house) decoded by our default decoder
// against the point RoboSense's own decoder computes for every valid return.
//
// The reference is rs_driver's arithmetic, written again here from its description (commit
// 4eeadac: decoder_RS16.hpp internDecodeMsopPkt L300–318 and RS16DifopPkt2Adapter L96–108,
// block_iterator.hpp Rs16SingleReturnBlockIterator, decoder_mech.hpp L186, trigon.hpp), not
// from our decoder:
//  - vertical angle: the DIFOP's 0.0001° value truncated to 0.01° ((uint16_t)(v · 0.01)),
//    channels 0–7 negative;
//  - block azimuth step: to the next block (wrapped), 2 · 20 (0.01°) when above 100 and for
//    the packet's last block (20 = round(36000 · rps · 55.5 µs) at 600 rpm);
//  - slot azimuth: block azimuth + (int32)(float(step) · firing_µs / 111), firing 2.8 µs per
//    laser plus 55.5 µs for slots 16–31 (single return, this capture's mode);
//  - x = d·cos v·cos h + RX·cos h, y = −d·cos v·sin h − RX·sin h, z = d·sin v + RZ in float,
//    with float sine/cosine of whole 0.01° angles (RS16 has no horizontal calibration, so the
//    calibrated and the uncalibrated azimuth are the same), d = code · 0.005 m.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "lidar_reference_util.h"
#include "swlio/drivers/lidar_decoder_factory.h"
#include "test_data.h"

namespace swlio::drivers {
namespace {

constexpr char kCapture[] = "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap";
constexpr uint16_t kMsopPort = 2244;
constexpr uint16_t kDifopPort = 7788;
constexpr float kRxM = 0.03825f;   // rs_driver RS16 RX
constexpr float kRyM = -0.01088f;  // declared RY, unused by rs_driver (only for the figure below)

using Packet = std::vector<uint8_t>;

int U16(const Packet& p, size_t at) { return (p[at] << 8) | p[at + 1]; }

float SinCdeg(int32_t cdeg) {
  return static_cast<float>(std::sin(cdeg * 0.01 * std::numbers::pi / 180.0));
}
float CosCdeg(int32_t cdeg) {
  return static_cast<float>(std::cos(cdeg * 0.01 * std::numbers::pi / 180.0));
}

struct VendorPoint {
  float x, y, z, distance;
  int32_t azimuth_cdeg;  ///< the slot's azimuth, 0.01°, not wrapped
};

/// rs_driver's per-laser vertical angles, 0.01°, from the DIFOP's pitch_cali (byte 1165).
std::array<int32_t, 16> VendorVerticalCdeg(const Packet& difop) {
  std::array<int32_t, 16> v{};
  for (size_t i = 0; i < 16; ++i) {
    const size_t at = 1165 + 3 * i;
    const uint32_t raw =
        (uint32_t{difop[at]} << 16) | (uint32_t{difop[at + 1]} << 8) | difop[at + 2];
    const auto truncated = static_cast<uint16_t>(raw * 0.01);
    v[i] = i < 8 ? -truncated : truncated;
  }
  return v;
}

/// rs_driver's points of one single-return MSOP packet, slot by slot (NaN x for no return).
std::array<VendorPoint, 384> VendorPoints(const Packet& p, const std::array<int32_t, 16>& vert) {
  constexpr int32_t kNominalDiff = 2 * 20;
  std::array<VendorPoint, 384> out{};
  for (size_t blk = 0; blk < 12; ++blk) {
    const int32_t az = U16(p, 42 + blk * 100 + 2);
    int32_t diff = kNominalDiff;
    if (blk < 11) {
      diff = U16(p, 42 + (blk + 1) * 100 + 2) - az;
      if (diff < 0) diff += 36000;
      if (diff > 100) diff = kNominalDiff;
    }
    for (size_t chan = 0; chan < 32; ++chan) {
      const auto firing_us = static_cast<float>(static_cast<double>(chan % 16) * 2.8 +
                                                static_cast<double>(chan / 16) * 55.5);
      const float percent = firing_us / (55.5f * 2.0f);
      const int32_t h = az + static_cast<int32_t>(static_cast<float>(diff) * percent);
      const int32_t v = vert[chan % 16];
      const int code = U16(p, 42 + blk * 100 + 4 + chan * 3);
      const float d = static_cast<float>(code) * 0.005f;
      VendorPoint& q = out[blk * 32 + chan];
      q.x = d * CosCdeg(v) * CosCdeg(h) + kRxM * CosCdeg(h);
      q.y = -d * CosCdeg(v) * SinCdeg(h) - kRxM * SinCdeg(h);
      q.z = d * SinCdeg(v) + 0.0f;
      q.distance = d;
      q.azimuth_cdeg = h;
      if (code == 0 || code == 0xFFFF) q.x = std::nanf("");
    }
  }
  return out;
}

struct Capture {
  std::vector<Packet> msop;
  Packet difop;
};

Capture Load(const std::filesystem::path& path) {
  Capture c;
  for (auto& r : test::ReadUdpRecords(path)) {
    if (r.dst_port == kMsopPort) c.msop.push_back(std::move(r.payload));
    if (r.dst_port == kDifopPort && c.difop.empty()) c.difop = std::move(r.payload);
  }
  return c;
}

struct Comparison {
  test::DeviationStats stats;
  test::DeviationStats stats_if_ry_applied;  ///< hypothetical: vendor point + RY sideways
};

/// Every valid return decoded with `config` against the vendor's point of the same slot.
Comparison CompareWithVendor(const Capture& cap, const LidarConfig& config) {
  const auto decoder = MakeLidarDecoder(config);
  EXPECT_EQ(decoder->DecodeInfo(cap.difop), DecodeStatus::kOk);
  const auto vert = VendorVerticalCdeg(cap.difop);
  std::vector<double> dev, dev_ry, range;
  LidarPacketDecoder::ReturnBuffer buf;
  for (const Packet& p : cap.msop) {
    LidarPacketSummary s;
    EXPECT_EQ(decoder->DecodeData(p, buf, &s), DecodeStatus::kOk);
    const auto vendor = VendorPoints(p, vert);
    for (uint32_t i = 0; i < s.returns; ++i) {
      const LidarReturn& r = buf[i];
      const VendorPoint& q = vendor[r.slot];
      EXPECT_FALSE(std::isnan(q.x)) << "slot " << r.slot;
      dev.push_back(std::hypot(r.x_m - q.x, r.y_m - q.y, r.z_m - q.z));
      const double rx = kRyM * SinCdeg(q.azimuth_cdeg), ry = kRyM * CosCdeg(q.azimuth_cdeg);
      dev_ry.push_back(std::hypot(r.x_m - (q.x + rx), r.y_m - (q.y + ry), r.z_m - q.z));
      range.push_back(q.distance);
    }
  }
  return {test::Summarize(dev, range), test::Summarize(dev_ry, range)};
}

LidarConfig CaptureConfig() {
  LidarConfig c;  // model rs16, lens offset absent: the vendor's
  c.msop_port = kMsopPort;
  c.difop_port = kDifopPort;
  c.min_range_m = 0.0;  // every code but 0 and 0xFFFF
  c.max_range_m = 300.0;
  return c;
}

TEST(Rs16VendorGeometry, EveryValidReturnIsWhereRsDriverPutsIt) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  const Capture cap = Load(path);
  ASSERT_EQ(cap.msop.size(), 3000u);
  ASSERT_EQ(cap.difop.size(), 1248u);
  const Comparison c = CompareWithVendor(cap, CaptureConfig());
  test::Print("RS16, default geometry vs rs_driver", c.stats);
  test::Print("RS16, if RY were applied (rs_driver does not)", c.stats_if_ry_applied);
  RecordProperty("returns", static_cast<int>(c.stats.count));
  RecordProperty("median_deviation_um", static_cast<int>(c.stats.median_m * 1e6));
  RecordProperty("max_deviation_um", static_cast<int>(c.stats.max_m * 1e6));
  EXPECT_EQ(c.stats.count, 1'063'236u);  // data README: every valid return
  EXPECT_EQ(c.stats.within, c.stats.count);
}

// The comparison can tell: the manual's formula (no lens offset) is off by 3.8 cm.
TEST(Rs16VendorGeometry, TheManualsFormulaIsNotTheVendors) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  LidarConfig config = CaptureConfig();
  config.lens_offset_m = 0.0;
  const Comparison c = CompareWithVendor(Load(path), config);
  test::Print("RS16, lens offset 0 vs rs_driver", c.stats);
  EXPECT_LT(c.stats.Fraction(), 0.1);
  EXPECT_GT(c.stats.median_m, 0.03);
}

}  // namespace
}  // namespace swlio::drivers

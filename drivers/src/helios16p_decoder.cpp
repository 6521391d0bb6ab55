// RoboSense RS-Helios-16P packet decoder.
//
// Protocol summary. Sources: RoboSense rs_driver
// `src/rs_driver/driver/decoder/decoder_RSHELIOS.hpp` (packet structs RSHELIOSMsopPkt /
// RSHELIOSDifopPkt) and `decoder_RSHELIOS_16P.hpp` (constants), tier4/nebula commit c60082d
// `robosense_helios16P_decoder.hpp` (firing-time table), checked against the real capture in
// shared/data/rs_helios16p_nebula. All multi-byte fields big-endian.
//
// MSOP (UDP, 1248 bytes, factory port 6699):
//   0   id 55 AA 05 5A
//   20  timestamp: 6-byte seconds + 4-byte microseconds (UTC, lidar clock)
//   42  12 blocks × 100 bytes: FF EE, azimuth (u16, 0.01°), 32 channels × {distance u16
//       (0.0025 m/LSB, 0 = no return), intensity u8}
//   1242 packet index (4) + tail (2)
// Blocks are 55.56 µs apart (the capture advances 0.20° per block at 600 rpm: 1800 blocks per
// turn). In single-return mode channels c and c + 16 are laser c % 16 of two interleaved
// firing sequences. nebula lists the 32 firing offsets on a 111.12 µs scale and interpolates
// a channel's azimuth as `block_az + trunc(step × offset / 111.12)` in 0.01°, `step` being the
// azimuth gap to the next block (nominal step for the last block or across a gap > 1°). We keep
// that interpolation and report firing times as offset / 2, which places both sequences inside
// the 55.56 µs block the azimuth steps show. In dual-return mode (DIFOP return mode 0x00)
// channels 0–15 are the first and 16–31 the second return of one firing (rs_driver's
// Rs16DualReturnBlockIterator); no dual capture was available to check this.
//
// Point in the frame RoboSense's drivers publish (as for RS16: x forward at azimuth 0, y left,
// z up; azimuth clockwise seen from above), with the lens-centre offset L (rs_driver's Helios
// RX = 0.03498 m by default, helios16p::kLensRxM) on the uncalibrated azimuth, in float with
// 0.01° tables as rs_driver (decoder_RSHELIOS_16P.hpp L245–247 @ 4eeadac) and nebula c60082d
// compute it:
//   a = interpolated azimuth, af = a + horizontal calibration of the laser, v = elevation
//   x = r cos v cos af + L cos a,  y = −r cos v sin af − L sin a,  z = r sin v
//
// DIFOP (1248 bytes, port 7788): id A5 FF 00 5A 11 11 55 55; rpm u16 @8; MSOP port @24,
// DIFOP port @28; FOV start/end (0.01°) @32/@34; return mode @300; vertical angles @468 and
// horizontal angles @564, 32 × {sign u8 (0 positive, 1 negative, FF = not calibrated), u16
// 0.01°}; the 16P uses the first 16.

#include "swlio/drivers/helios16p_decoder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "swlio/drivers/bytes.h"
#include "swlio/drivers/detail/centideg_trig.h"

namespace swlio::drivers {
namespace {

using bytes::ReadU16Be;
using bytes::ReadUBe;

constexpr uint8_t kMsopId[4] = {0x55, 0xAA, 0x05, 0x5A};
constexpr uint8_t kDifopId[8] = {0xA5, 0xFF, 0x00, 0x5A, 0x11, 0x11, 0x55, 0x55};
constexpr size_t kTimeOffset = 20;
constexpr size_t kFirstBlock = 42;
constexpr size_t kBlockBytes = 100;
constexpr size_t kBlocks = 12;
constexpr size_t kChannels = 32;
constexpr size_t kLasers = 16;
constexpr float kDistanceLsbM = 0.0025f;
constexpr double kBlockUs = 55.56;
constexpr int64_t kBlockNs = 55560;
constexpr int32_t kMaxPlausibleStepCdeg = 100;  // rs_driver: larger gaps are FOV blind zones

// nebula c60082d firing offsets, µs on the 111.12 µs (two-block) scale.
constexpr float kFiringUs[kChannels] = {
    0.00f,  3.15f,  6.30f,  9.45f,  13.26f, 17.08f, 20.56f, 23.71f, 26.53f, 27.77f, 31.49f,
    32.73f, 36.46f, 38.94f, 41.42f, 43.91f, 55.56f, 58.70f, 61.85f, 65.00f, 68.82f, 72.64f,
    76.12f, 79.27f, 82.08f, 83.32f, 87.05f, 88.29f, 92.01f, 94.50f, 96.98f, 99.46f};

// DIFOP offsets (rs_driver RSHELIOSDifopPkt).
constexpr size_t kDifopRpm = 8;
constexpr size_t kDifopMsopPort = 24;
constexpr size_t kDifopDifopPort = 28;
constexpr size_t kDifopFovStart = 32;
constexpr size_t kDifopFovEnd = 34;
constexpr size_t kDifopReturnMode = 300;
constexpr size_t kDifopVertical = 468;
constexpr size_t kDifopHorizontal = 564;

bool HasPrefix(std::span<const uint8_t> p, const uint8_t* id, size_t n) {
  return p.size() >= n && std::equal(id, id + n, p.begin());
}

int32_t ToCdeg(double deg) { return static_cast<int32_t>(std::lround(deg * 100.0)); }

// One DIFOP angle {sign, u16 BE}; false when the slot is uncalibrated or out of ±90°.
bool ReadDifopAngle(const uint8_t* p, int32_t* cdeg) {
  if (p[0] > 1) return false;
  const int32_t v = ReadU16Be(p + 1);
  if (v >= 9000) return false;
  *cdeg = p[0] == 0 ? v : -v;
  return true;
}

}  // namespace

Helios16pDecoder::Helios16pDecoder(const Helios16pOptions& options) : options_(options) {
  std::array<int32_t, 16> vert{};
  std::array<int32_t, 16> horiz{};
  for (size_t i = 0; i < kLasers; ++i) {
    vert[i] = ToCdeg(options.calibration.vertical_deg[i]);
    horiz[i] = ToCdeg(options.calibration.horizontal_deg[i]);
  }
  SetCalibration(vert, horiz);
  SetRpm(options.rpm);
}

void Helios16pDecoder::SetCalibration(const std::array<int32_t, 16>& vert_cdeg,
                                      const std::array<int32_t, 16>& horiz_cdeg) {
  const auto& trig = detail::CentidegTrig::Get();
  vert_cdeg_ = vert_cdeg;
  horiz_cdeg_ = horiz_cdeg;
  for (size_t i = 0; i < kLasers; ++i) {
    sin_vert_[i] = trig.Sin(vert_cdeg[i]);
    cos_vert_[i] = trig.Cos(vert_cdeg[i]);
    // Ring = rank by elevation (ties broken by laser index so rings stay distinct).
    uint16_t rank = 0;
    for (size_t j = 0; j < kLasers; ++j) {
      if (vert_cdeg[j] < vert_cdeg[i] || (vert_cdeg[j] == vert_cdeg[i] && j < i)) ++rank;
    }
    ring_[i] = rank;
  }
}

void Helios16pDecoder::SetRpm(double rpm) {
  if (!(rpm > 0.0) || !std::isfinite(rpm)) return;
  rpm_ = rpm;
  nominal_block_step_cdeg_ =
      static_cast<int32_t>(std::lround(36000.0 * rpm / 60.0 * kBlockUs * 1e-6));
}

LidarPacketKind Helios16pDecoder::Classify(std::span<const uint8_t> packet) const {
  if (packet.size() != kPacketBytes) return LidarPacketKind::kUnknown;
  if (HasPrefix(packet, kMsopId, sizeof(kMsopId))) return LidarPacketKind::kData;
  if (HasPrefix(packet, kDifopId, sizeof(kDifopId))) return LidarPacketKind::kInfo;
  return LidarPacketKind::kUnknown;
}

double Helios16pDecoder::PacketsPerRevolution() const {
  return 60.0 / rpm_ / (static_cast<double>(kBlocks) * kBlockUs * 1e-6);
}

DecodeStatus Helios16pDecoder::DecodeData(std::span<const uint8_t> packet,
                                          std::span<LidarReturn> out,
                                          LidarPacketSummary* summary) const {
  if (packet.size() != kPacketBytes) return DecodeStatus::kWrongSize;
  if (!HasPrefix(packet, kMsopId, sizeof(kMsopId))) return DecodeStatus::kBadHeader;
  const uint8_t* p = packet.data();
  for (size_t b = 0; b < kBlocks; ++b) {
    const uint8_t* blk = p + kFirstBlock + b * kBlockBytes;
    if (blk[0] != 0xFF || blk[1] != 0xEE || ReadU16Be(blk + 2) >= 36000) {
      return DecodeStatus::kBadHeader;
    }
  }
  const uint64_t sec = ReadUBe(p + kTimeOffset, 6);
  const uint64_t usec = ReadUBe(p + kTimeOffset + 6, 4);
  constexpr uint64_t kMaxSec = std::numeric_limits<int64_t>::max() / 1'000'000'000 - 1;
  if (sec > kMaxSec || usec >= 1'000'000) return DecodeStatus::kBadHeader;
  if (out.size() < kBlocks * kChannels) return DecodeStatus::kBufferTooSmall;

  LidarPacketSummary s;
  s.t_sensor_ns = static_cast<int64_t>(sec) * 1'000'000'000 + static_cast<int64_t>(usec) * 1000;
  s.first_azimuth_deg = static_cast<float>(ReadU16Be(p + kFirstBlock + 2)) * 0.01f;
  s.last_azimuth_deg =
      static_cast<float>(ReadU16Be(p + kFirstBlock + (kBlocks - 1) * kBlockBytes + 2)) * 0.01f;
  s.return_mode = mode_;
  for (size_t b = 0; b < kBlocks; ++b) {
    const uint8_t* blk = p + kFirstBlock + b * kBlockBytes;
    int32_t step = nominal_block_step_cdeg_;
    if (b + 1 < kBlocks) {
      const int32_t az = ReadU16Be(blk + 2);
      const int32_t next = ReadU16Be(blk + kBlockBytes + 2);
      const int32_t diff = detail::CentidegTrig::Wrap(next - az);
      if (diff <= kMaxPlausibleStepCdeg) step = diff;
    }
    DecodeBlock(blk, step, s.t_sensor_ns + static_cast<int64_t>(b) * kBlockNs, out, &s);
  }
  if (summary != nullptr) *summary = s;
  return DecodeStatus::kOk;
}

void Helios16pDecoder::DecodeBlock(const uint8_t* block,
                                   int32_t az_step_cdeg,
                                   int64_t t_block_ns,
                                   std::span<LidarReturn> out,
                                   LidarPacketSummary* s) const {
  const auto& trig = detail::CentidegTrig::Get();
  const bool dual = mode_ == ReturnMode::kDual;
  const int32_t block_az = ReadU16Be(block + 2);
  const float min_r = static_cast<float>(options_.min_range_m);
  const float max_r = static_cast<float>(options_.max_range_m);
  const float lens_m = static_cast<float>(options_.lens_offset_m);
  for (size_t c = 0; c < kChannels; ++c) {
    const uint8_t* ch = block + 4 + 3 * c;
    const float range = static_cast<float>(ReadU16Be(ch)) * kDistanceLsbM;
    if (!(range >= min_r && range <= max_r) || range <= 0.0f) {
      ++s->no_returns;
      continue;
    }
    const size_t laser = c % kLasers;
    const size_t timing = dual ? laser : c;  // dual: both returns share one firing
    const float frac = kFiringUs[timing] / static_cast<float>(kBlockUs * 2.0);
    const int32_t az = block_az + static_cast<int32_t>(static_cast<float>(az_step_cdeg) * frac);
    const int32_t az_final = az + horiz_cdeg_[laser];
    const float xy = range * cos_vert_[laser];
    LidarReturn& r = out[s->returns++];
    r.x_m = xy * trig.Cos(az_final) + lens_m * trig.Cos(az);
    r.y_m = -xy * trig.Sin(az_final) - lens_m * trig.Sin(az);
    r.z_m = range * sin_vert_[laser];
    r.range_m = range;
    r.azimuth_deg = static_cast<float>(detail::CentidegTrig::Wrap(az_final)) * 0.01f;
    r.intensity = static_cast<float>(ch[2]);
    r.ring = ring_[laser];
    r.return_index = static_cast<uint8_t>(dual && c >= kLasers ? 1 : 0);
    r.t_sensor_ns = t_block_ns + static_cast<int64_t>(std::lround(kFiringUs[timing] * 500.0f));
  }
}

DecodeStatus Helios16pDecoder::DecodeInfo(std::span<const uint8_t> packet) {
  if (packet.size() != kPacketBytes) return DecodeStatus::kWrongSize;
  if (!HasPrefix(packet, kDifopId, sizeof(kDifopId))) return DecodeStatus::kBadHeader;
  const uint8_t* p = packet.data();
  info_.difop_seen = true;
  info_.rpm = ReadU16Be(p + kDifopRpm);
  info_.msop_port = ReadU16Be(p + kDifopMsopPort);
  info_.difop_port = ReadU16Be(p + kDifopDifopPort);
  info_.fov_start_cdeg = ReadU16Be(p + kDifopFovStart);
  info_.fov_end_cdeg = ReadU16Be(p + kDifopFovEnd);
  info_.return_mode_byte = p[kDifopReturnMode];
  switch (info_.return_mode_byte) {
    case 0x00:
      mode_ = ReturnMode::kDual;
      break;
    case 0x04:
      mode_ = ReturnMode::kStrongest;
      break;
    case 0x05:
      mode_ = ReturnMode::kLast;
      break;
    default:
      mode_ = ReturnMode::kUnknown;
      break;  // 0x06 nearest etc.: decoded as single
  }
  if (info_.rpm != 0) SetRpm(info_.rpm);

  std::array<int32_t, 16> vert{};
  std::array<int32_t, 16> horiz{};
  bool valid = true;
  for (size_t i = 0; i < kLasers && valid; ++i) {
    valid = ReadDifopAngle(p + kDifopVertical + 3 * i, &vert[i]) &&
            ReadDifopAngle(p + kDifopHorizontal + 3 * i, &horiz[i]);
  }
  info_.calibration_from_difop = valid;
  if (valid) SetCalibration(vert, horiz);
  return DecodeStatus::kOk;
}

}  // namespace swlio::drivers

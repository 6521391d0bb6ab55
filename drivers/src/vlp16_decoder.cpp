// Velodyne VLP-16 data-packet decoder.
//
// Protocol summary. Source: Velodyne "VLP-16 User Manual" (63-9243 Rev. D/E), ch. 9 "Sensor
// Data" and "Firing Timing"; checked against the real capture in shared/data/velodyne_nebula.
// All multi-byte fields little-endian.
//
// Data packet (UDP, 1206 bytes, port 2368; the sensor sends no DIFOP on this port):
//   0    12 blocks × 100 bytes: flag FF EE, azimuth u16 (0.01°, 0–35999), then 2 firing
//        sequences × 16 lasers × {distance u16 (2 mm/LSB, 0 = no return), reflectivity u8}
//   1200 timestamp u32: µs past the top of the hour, time of the first firing of block 0
//   1204 return mode: 0x37 strongest, 0x38 last, 0x39 dual;  1205 product id 0x22 = VLP-16
// Laser ids 0–15 point at −15, 1, −13, 3, −11, 5, −9, 7, −7, 9, −5, 11, −3, 13, −1, 15 degrees.
// Firing timing: one laser every 2.304 µs, one firing sequence every 55.296 µs (16 firings +
// recharge), two sequences per block in single-return mode. In dual-return mode a block pair
// (2k, 2k + 1) holds the last and the strongest return of the same two sequences.
// Azimuth of a firing (manual's interpolation): block azimuth + gap × t_in_block / 110.592 µs,
// the gap being the azimuth advance to the next block (pair); the last block (pair) of a packet
// reuses the previous gap. Azimuth is rounded to 0.01° for the sine/cosine table.
//
// Point in the frame Velodyne's ROS driver publishes (ros-drivers/velodyne `rawdata.cc`
// unpack_vlp16, "Use standard ROS coordinate system", L800–802 @ 29abd0e; nebula the same):
// x forward at azimuth 0, y left, z up; azimuth clockwise seen from above:
//   x = r cos ω cos α + L cos α,  y = −r cos ω sin α − L sin α,  z = r sin ω
// with the lens offset L of Vlp16Options (0 by default, as Velodyne's calibration files have
// every offset correction 0). The manual's per-laser vertical offsets (±11.2 mm) are not
// applied, as neither driver applies them with the stock calibration.

#include "swlio/drivers/vlp16_decoder.h"

#include <cmath>

#include "swlio/drivers/bytes.h"
#include "swlio/drivers/detail/centideg_trig.h"

namespace swlio::drivers {
namespace {

using bytes::ReadU16Le;
using bytes::ReadU32Le;

constexpr size_t kBlocks = 12;
constexpr size_t kBlockBytes = 100;
constexpr size_t kLasers = 16;
constexpr size_t kTimestampOffset = 1200;
constexpr size_t kReturnModeOffset = 1204;
constexpr size_t kProductOffset = 1205;
constexpr uint8_t kModeStrongest = 0x37;
constexpr uint8_t kModeLast = 0x38;
constexpr uint8_t kModeDual = 0x39;
constexpr uint8_t kProductVlp16 = 0x22;
constexpr float kDistanceLsbM = 0.002f;
constexpr double kFiringUs = 2.304;
constexpr double kSequenceUs = 55.296;
constexpr int64_t kFiringNs = 2304;
constexpr int64_t kSequenceNs = 55296;
constexpr uint32_t kUsPerHour = 3'600'000'000u;
constexpr int kElevationDeg[kLasers] = {-15, 1, -13, 3,  -11, 5,  -9, 7,
                                        -7,  9, -5,  11, -3,  13, -1, 15};

int32_t BlockAzimuth(const uint8_t* packet, size_t block) {
  return ReadU16Le(packet + block * kBlockBytes + 2);
}

// Azimuth advance (0.01°) from `block` to the block `stride` later; the last block(s) of the
// packet reuse the previous gap, as the manual suggests.
float StepCdeg(const uint8_t* packet, size_t block, size_t stride) {
  size_t from = block - block % stride;
  if (from + stride >= kBlocks) from = from >= stride ? from - stride : 0;
  if (from + stride >= kBlocks) return 0.0f;
  const int32_t gap =
      detail::CentidegTrig::Wrap(BlockAzimuth(packet, from + stride) - BlockAzimuth(packet, from));
  return static_cast<float>(gap);
}

}  // namespace

Vlp16Decoder::Vlp16Decoder(const Vlp16Options& options) : options_(options) {
  const auto& trig = detail::CentidegTrig::Get();
  for (size_t i = 0; i < kLasers; ++i) {
    sin_vert_[i] = trig.Sin(kElevationDeg[i] * 100);
    cos_vert_[i] = trig.Cos(kElevationDeg[i] * 100);
  }
}

double Vlp16Decoder::ElevationDeg(size_t laser) { return kElevationDeg[laser % kLasers]; }

uint16_t Vlp16Decoder::RingOfLaser(size_t laser) {
  // Even ids run −15…−1 (rings 0–7), odd ids 1…15 (rings 8–15).
  const size_t l = laser % kLasers;
  return static_cast<uint16_t>(l % 2 == 0 ? l / 2 : 8 + l / 2);
}

LidarPacketKind Vlp16Decoder::Classify(std::span<const uint8_t> packet) const {
  if (packet.size() != kPacketBytes) return LidarPacketKind::kUnknown;
  return packet[0] == 0xFF && packet[1] == 0xEE ? LidarPacketKind::kData
                                                : LidarPacketKind::kUnknown;
}

double Vlp16Decoder::PacketsPerRevolution() const {
  const double sequences_per_packet = options_.dual_return ? 12.0 : 24.0;
  return 60.0 / options_.rpm / (sequences_per_packet * kSequenceUs * 1e-6);
}

DecodeStatus Vlp16Decoder::DecodeInfo(std::span<const uint8_t> packet) {
  return packet.size() == kPacketBytes ? DecodeStatus::kBadHeader : DecodeStatus::kWrongSize;
}

DecodeStatus Vlp16Decoder::DecodeData(std::span<const uint8_t> packet,
                                      std::span<LidarReturn> out,
                                      LidarPacketSummary* summary) const {
  if (packet.size() != kPacketBytes) return DecodeStatus::kWrongSize;
  const uint8_t* p = packet.data();
  for (size_t b = 0; b < kBlocks; ++b) {
    const uint8_t* blk = p + b * kBlockBytes;
    if (blk[0] != 0xFF || blk[1] != 0xEE || BlockAzimuth(p, b) >= 36000) {
      return DecodeStatus::kBadHeader;
    }
  }
  const uint8_t mode = p[kReturnModeOffset];
  const uint32_t t_us = ReadU32Le(p + kTimestampOffset);
  if (p[kProductOffset] != kProductVlp16 || t_us >= kUsPerHour ||
      (mode != kModeStrongest && mode != kModeLast && mode != kModeDual)) {
    return DecodeStatus::kBadHeader;
  }
  if (out.size() < kBlocks * 2 * kLasers) return DecodeStatus::kBufferTooSmall;

  LidarPacketSummary s;
  s.t_sensor_ns = static_cast<int64_t>(t_us) * 1000;
  s.first_azimuth_deg = static_cast<float>(BlockAzimuth(p, 0)) * 0.01f;
  s.last_azimuth_deg = static_cast<float>(BlockAzimuth(p, kBlocks - 1)) * 0.01f;
  s.return_mode = mode == kModeDual   ? ReturnMode::kDual
                  : mode == kModeLast ? ReturnMode::kLast
                                      : ReturnMode::kStrongest;
  const bool dual = mode == kModeDual;
  for (size_t b = 0; b < kBlocks; ++b) {
    DecodeBlock(p, b, dual, StepCdeg(p, b, dual ? 2 : 1), s.t_sensor_ns, out, &s);
  }
  if (summary != nullptr) *summary = s;
  return DecodeStatus::kOk;
}

void Vlp16Decoder::DecodeBlock(const uint8_t* packet,
                               size_t block,
                               bool dual,
                               float step_cdeg,
                               int64_t t_packet_ns,
                               std::span<LidarReturn> out,
                               LidarPacketSummary* s) const {
  const auto& trig = detail::CentidegTrig::Get();
  const uint8_t* blk = packet + block * kBlockBytes;
  const uint8_t* partner = dual ? packet + (block ^ 1u) * kBlockBytes : nullptr;
  const bool second = dual && block % 2 == 1;
  const size_t first_sequence = dual ? block - block % 2 : 2 * block;
  const float az0 = static_cast<float>(BlockAzimuth(packet, block));
  const float min_r = static_cast<float>(options_.min_range_m);
  const float max_r = static_cast<float>(options_.max_range_m);
  const float lens_m = static_cast<float>(options_.lens_offset_m);
  for (size_t f = 0; f < 2; ++f) {
    for (size_t l = 0; l < kLasers; ++l) {
      const size_t off = 4 + 3 * (f * kLasers + l);
      const uint16_t raw = ReadU16Le(blk + off);
      if (second && raw != 0 && raw == ReadU16Le(partner + off)) continue;  // duplicate
      const float range = static_cast<float>(raw) * kDistanceLsbM;
      if (raw == 0 || !(range >= min_r && range <= max_r)) {
        ++s->no_returns;
        continue;
      }
      const double t_in_block_us =
          static_cast<double>(f) * kSequenceUs + static_cast<double>(l) * kFiringUs;
      const float az_f = az0 + step_cdeg * static_cast<float>(t_in_block_us / (2 * kSequenceUs));
      const int32_t az = detail::CentidegTrig::Wrap(static_cast<int32_t>(std::lround(az_f)));
      const float xy = range * cos_vert_[l] + lens_m;
      LidarReturn& r = out[s->returns++];
      r.x_m = xy * trig.Cos(az);
      r.y_m = -xy * trig.Sin(az);
      r.z_m = range * sin_vert_[l];
      r.range_m = range;
      r.azimuth_deg = static_cast<float>(az) * 0.01f;
      r.intensity = static_cast<float>(blk[off + 2]);
      r.ring = RingOfLaser(l);
      r.return_index = static_cast<uint8_t>(second ? 1 : 0);
      r.t_sensor_ns = t_packet_ns + static_cast<int64_t>(first_sequence + f) * kSequenceNs +
                      static_cast<int64_t>(l) * kFiringNs;
    }
  }
}

}  // namespace swlio::drivers

// RS-LiDAR-16 MSOP/DIFOP encoding. Protocol summary and sources: rs16_protocol.h.

#include "swlio/drivers/rs16_encoder.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "swlio/drivers/bytes.h"

namespace swlio::drivers {
namespace {

using namespace rs16;  // NOLINT: the protocol constants are this file's vocabulary

uint16_t RawDistance(float range_m, double resolution_m) {
  const double raw = std::round(static_cast<double>(range_m) / resolution_m);
  if (!(raw >= 1.0)) return kNoReturnZero;
  return static_cast<uint16_t>(std::min(raw, 65534.0));
}

uint16_t RawAzimuth(double azimuth_deg) {
  double cdeg = std::round(azimuth_deg / kAzimuthResolutionDeg);
  if (!std::isfinite(cdeg)) cdeg = 0.0;
  cdeg = std::fmod(cdeg, 36000.0);
  if (cdeg < 0.0) cdeg += 36000.0;
  return static_cast<uint16_t>(cdeg);
}

uint8_t ModeByte(ReturnMode mode) {
  switch (mode) {
    case ReturnMode::kDual:
      return kReturnModeDual;
    case ReturnMode::kLast:
      return kReturnModeLast;
    default:
      return kReturnModeStrongest;
  }
}

}  // namespace

size_t FillRs16Slots(std::span<const LidarReturn> returns, Rs16MsopContent* content) {
  size_t used = 0;
  for (const LidarReturn& r : returns) {
    if (r.slot >= kBlocks * kSlotsPerBlock) continue;
    auto& block = content->blocks[r.slot / kSlotsPerBlock];
    block.range_m[r.slot % kSlotsPerBlock] = r.range_m;
    const float intensity = r.intensity >= 0.0f ? std::min(r.intensity, 255.0f) : 0.0f;  // NaN → 0
    block.intensity[r.slot % kSlotsPerBlock] = static_cast<uint8_t>(std::lround(intensity));
    ++used;
  }
  return used;
}

float RangeOfPoint(float x_m, float y_m, float z_m, double azimuth_deg, double lens_offset_m) {
  const double a = azimuth_deg * std::numbers::pi / 180.0;
  const double dx = x_m - lens_offset_m * std::cos(a);
  const double dy = y_m + lens_offset_m * std::sin(a);
  return static_cast<float>(std::sqrt(dx * dx + dy * dy + static_cast<double>(z_m) * z_m));
}

bool EncodeRs16Msop(const Rs16MsopContent& content, std::span<uint8_t> out) {
  if (out.size() != kPacketBytes || !(content.distance_resolution_m > 0.0)) return false;
  std::fill(out.begin(), out.end(), uint8_t{0});
  uint8_t* p = out.data();
  std::copy(kMsopId.begin(), kMsopId.end(), p);
  if (!WriteTime(p + kTimeOffset, content.time_format, content.t_sensor_ns)) return false;
  p[kLidarTypeOffset] = content.lidar_type;
  for (size_t b = 0; b < kBlocks; ++b) {
    uint8_t* blk = p + kFirstBlockOffset + b * kBlockBytes;
    const Rs16BlockContent& block = content.blocks[b];
    blk[0] = kBlockFlag0;
    blk[1] = kBlockFlag1;
    bytes::WriteU16Be(blk + 2, RawAzimuth(block.azimuth_deg));
    for (size_t s = 0; s < kSlotsPerBlock; ++s) {
      uint8_t* slot = blk + 4 + s * kSlotBytes;
      bytes::WriteU16Be(slot, RawDistance(block.range_m[s], content.distance_resolution_m));
      slot[2] = block.intensity[s];
    }
  }
  bytes::WriteU16Be(p + kTailOffset + 4, 0x00FF);  // tail as seen on the real unit: .. 00 FF
  return true;
}

bool EncodeRs16Difop(const Rs16DifopContent& content, std::span<uint8_t> out) {
  if (out.size() != kPacketBytes) return false;
  std::fill(out.begin(), out.end(), uint8_t{0});
  uint8_t* p = out.data();
  std::copy(kDifopId.begin(), kDifopId.end(), p);
  bytes::WriteU16Be(p + kDifopRpm, content.rpm);
  std::copy(content.lidar_ip.begin(), content.lidar_ip.end(), p + kDifopLidarIp);
  std::copy(content.host_ip.begin(), content.host_ip.end(), p + kDifopHostIp);
  std::copy(content.mac.begin(), content.mac.end(), p + kDifopMac);
  bytes::WriteU16Be(p + kDifopMsopSrcPort, content.msop_port);
  bytes::WriteU16Be(p + kDifopMsopDstPort, content.msop_port);
  bytes::WriteU16Be(p + kDifopDifopSrcPort, content.difop_port);
  bytes::WriteU16Be(p + kDifopDifopDstPort, content.difop_port);
  bytes::WriteU16Be(
      p + kDifopFovStart,
      static_cast<uint16_t>(std::lround(std::clamp(content.fov_start_deg, 0.0, 360.0) * 100)));
  bytes::WriteU16Be(
      p + kDifopFovEnd,
      static_cast<uint16_t>(std::lround(std::clamp(content.fov_end_deg, 0.0, 360.0) * 100)));
  std::copy(content.top_firmware.begin(), content.top_firmware.end(), p + kDifopTopFirmware);
  std::copy(content.bottom_firmware.begin(), content.bottom_firmware.end(),
            p + kDifopBottomFirmware);
  p[kDifopReturnMode] = ModeByte(content.return_mode);
  if (content.t_sensor_ns > 0) WriteTime(p + kDifopTime, TimeFormat::kYmd, content.t_sensor_ns);
  for (size_t i = 0; i < kLasers; ++i) {
    const double a = content.vertical_angles_deg[i];
    if ((i < 8 && a > 0.0) || (i >= 8 && a < 0.0) || !(std::abs(a) <= 90.0)) return false;
    const auto magnitude =
        static_cast<uint64_t>(std::lround(std::abs(a) / kPitchCaliResolutionDeg));
    bytes::WriteUBe(p + kDifopPitchCali + 3 * i, magnitude, 3);
  }
  std::fill(p + kDifopPitchCali + 48, p + kPacketBytes - 2, uint8_t{0xFF});
  bytes::WriteU16Be(p + kPacketBytes - 2, 0x0FF0);  // tail as seen on the real unit
  return true;
}

}  // namespace swlio::drivers

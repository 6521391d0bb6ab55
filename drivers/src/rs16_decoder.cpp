// RS-LiDAR-16 MSOP/DIFOP decoding. Protocol summary and sources: rs16_protocol.h
// (rs_driver decoder_RS16.hpp, basic_attr.hpp, block_iterator.hpp; RS-LiDAR-16 User Manual).

#include "swlio/drivers/rs16_decoder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "swlio/drivers/bytes.h"

namespace swlio::drivers {
namespace {

using namespace rs16;  // NOLINT: the protocol constants are this file's vocabulary

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kCdegToRad = kDegToRad * kAzimuthResolutionDeg;
constexpr int kCdegPerTurn = 36000;

bool HasId(std::span<const uint8_t> packet, const std::array<uint8_t, 8>& id) {
  return packet.size() >= id.size() && std::equal(id.begin(), id.end(), packet.begin());
}

// Distance codes accepted by [min_range_m, max_range_m]; codes 0 and 0xFFFF never are.
uint16_t MinRawDistance(double min_range_m, double resolution_m) {
  const double raw = std::ceil(min_range_m / resolution_m);
  return static_cast<uint16_t>(std::clamp(std::isfinite(raw) ? raw : 1.0, 1.0, 65534.0));
}
uint16_t MaxRawDistance(double max_range_m, double resolution_m) {
  const double raw = std::floor(max_range_m / resolution_m);
  return static_cast<uint16_t>(std::clamp(std::isnan(raw) ? 0.0 : raw, 0.0, 65534.0));
}

ReturnMode ModeFromByte(uint8_t b) {
  switch (b) {
    case kReturnModeDual:
      return ReturnMode::kDual;
    case kReturnModeStrongest:
      return ReturnMode::kStrongest;
    case kReturnModeLast:
      return ReturnMode::kLast;
    default:
      return ReturnMode::kUnknown;
  }
}

// Top-board firmware bytes 41–43 of the units that count distance in 10 mm (ros_rslidar).
bool IsOldTopFirmware(const uint8_t* b) {
  constexpr std::array<std::array<uint8_t, 3>, 4> kOld = {
      {{0x00, 0x00, 0x00}, {0xFF, 0xFF, 0xFF}, {0x55, 0xAA, 0x5A}, {0xE9, 0x01, 0x00}}};
  return std::any_of(kOld.begin(), kOld.end(),
                     [b](const auto& v) { return std::equal(v.begin(), v.end(), b); });
}

// pitch_cali: 16 × 24-bit big-endian magnitudes in 0.0001°, channels 0–7 negative
// (rs_driver decoder_RS16.hpp). Blank when the first 4 bytes are each 0x00 or 0xFF.
// Fills has_vertical_calibration (and the angles) or damaged_vertical_calibration; a blank
// field (a unit without calibration) is neither.
void ParsePitchCali(const uint8_t* p, Rs16DifopInfo* d) {
  const bool blank = std::all_of(p, p + 4, [](uint8_t b) { return b == 0x00 || b == 0xFF; });
  if (blank) return;
  std::array<double, 16> a{};
  for (size_t i = 0; i < a.size(); ++i) {
    const double magnitude =
        static_cast<double>(bytes::ReadUBe(p + 3 * i, 3)) * kPitchCaliResolutionDeg;
    if (magnitude > 90.0) {
      d->damaged_vertical_calibration = true;
      return;
    }
    a[i] = i < 8 ? -magnitude : magnitude;
  }
  d->vertical_angles_deg = a;
  d->has_vertical_calibration = true;
}

// Block flags FF EE and azimuths (0.01°, < 36000) of all 12 blocks; false when any is invalid.
bool ReadBlockAzimuths(const uint8_t* p, std::array<int, kBlocks>* az) {
  for (size_t b = 0; b < kBlocks; ++b) {
    const uint8_t* blk = p + kFirstBlockOffset + b * kBlockBytes;
    (*az)[b] = bytes::ReadU16Be(blk + 2);
    if (blk[0] != kBlockFlag0 || blk[1] != kBlockFlag1 || (*az)[b] >= kCdegPerTurn) return false;
  }
  return true;
}

// Block azimuth step in 0.01°: to the next block, the previous step for the last block, and
// the nominal step where the measured one jumps (FOV edge, corrupted azimuth).
void BlockSteps(const std::array<int, kBlocks>& az,
                double nominal,
                std::array<double, kBlocks>* s) {
  for (size_t b = 0; b + 1 < kBlocks; ++b) {
    const int diff = (az[b + 1] - az[b] + kCdegPerTurn) % kCdegPerTurn;
    const double d = static_cast<double>(diff);
    (*s)[b] = d > std::max(2.0 * nominal, 10.0) ? nominal : d;
  }
  (*s)[kBlocks - 1] = (*s)[kBlocks - 2];
}

}  // namespace

DecodeStatus ParseRs16Difop(std::span<const uint8_t> packet, Rs16DifopInfo* info) {
  if (packet.size() != kPacketBytes) return DecodeStatus::kWrongSize;
  if (!HasId(packet, kDifopId)) return DecodeStatus::kBadHeader;
  const uint8_t* p = packet.data();
  Rs16DifopInfo d;
  d.rpm = bytes::ReadU16Be(p + kDifopRpm);
  std::copy_n(p + kDifopLidarIp, 4, d.lidar_ip.begin());
  std::copy_n(p + kDifopHostIp, 4, d.host_ip.begin());
  std::copy_n(p + kDifopMac, 6, d.mac.begin());
  d.msop_src_port = bytes::ReadU16Be(p + kDifopMsopSrcPort);
  d.msop_dst_port = bytes::ReadU16Be(p + kDifopMsopDstPort);
  d.difop_src_port = bytes::ReadU16Be(p + kDifopDifopSrcPort);
  d.difop_dst_port = bytes::ReadU16Be(p + kDifopDifopDstPort);
  d.fov_start_deg = bytes::ReadU16Be(p + kDifopFovStart) * kAzimuthResolutionDeg;
  d.fov_end_deg = bytes::ReadU16Be(p + kDifopFovEnd) * kAzimuthResolutionDeg;
  std::copy_n(p + kDifopTopFirmware, 5, d.top_firmware.begin());
  std::copy_n(p + kDifopBottomFirmware, 5, d.bottom_firmware.begin());
  d.distance_resolution_m =
      IsOldTopFirmware(p + kDifopTopFirmware + 1) ? kOldDistanceResolutionM : kDistanceResolutionM;
  const uint8_t* bottom = p + kDifopBottomFirmware;
  d.supports_dual_return = bottom[0] > 0x08 || (bottom[0] == 0x08 && bottom[1] > 0x02) ||
                           (bottom[0] == 0x08 && bottom[1] == 0x02 && bottom[2] >= 0x09);
  d.return_mode =
      d.supports_dual_return ? ModeFromByte(p[kDifopReturnMode]) : ReturnMode::kStrongest;
  d.time_valid = ParseTime(p + kDifopTime, TimeFormat::kYmd, &d.t_sensor_ns);
  ParsePitchCali(p + kDifopPitchCali, &d);
  *info = d;
  return DecodeStatus::kOk;
}

Rs16Decoder::Rs16Decoder(const LidarConfig& config, Rs16DecoderOptions options)
    : options_(options),
      rpm_(config.rpm > 0.0 ? config.rpm : 600.0),
      return_mode_(options.initial_return_mode),
      min_range_m_(config.min_range_m),
      max_range_m_(config.max_range_m) {
  SetResolution(options.distance_resolution_m > 0.0 ? options.distance_resolution_m
                                                    : kDistanceResolutionM);
  for (int c = 0; c < kLasers; ++c) {
    const auto i = static_cast<size_t>(c);
    vertical_deg_[i] = config.vertical_angles_deg[kNominalRingOfChannel[i]];
  }
  configured_vertical_deg_ = vertical_deg_;
  UpdateLaserTables();
}

void Rs16Decoder::SetCalibration(const std::array<double, 16>& vertical_deg_by_channel,
                                 const std::array<double, 16>& horizontal_deg_by_channel) {
  vertical_deg_ = vertical_deg_by_channel;
  horizontal_deg_ = horizontal_deg_by_channel;
  UpdateLaserTables();
}

void Rs16Decoder::SetResolution(double resolution_m) {
  resolution_m_ = resolution_m;
  min_raw_ = MinRawDistance(min_range_m_, resolution_m);
  max_raw_ = MaxRawDistance(max_range_m_, resolution_m);
}

void Rs16Decoder::UpdateLaserTables() {
  std::array<uint16_t, 16> order{};
  std::iota(order.begin(), order.end(), uint16_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [this](uint16_t a, uint16_t b) { return vertical_deg_[a] < vertical_deg_[b]; });
  for (size_t rank = 0; rank < order.size(); ++rank)
    ring_[order[rank]] = static_cast<uint16_t>(rank);
  for (size_t i = 0; i < 16; ++i) {
    cos_vert_[i] = std::cos(vertical_deg_[i] * kDegToRad);
    sin_vert_[i] = std::sin(vertical_deg_[i] * kDegToRad);
    cos_horiz_[i] = std::cos(horizontal_deg_[i] * kDegToRad);
    sin_horiz_[i] = std::sin(horizontal_deg_[i] * kDegToRad);
  }
}

LidarPacketKind Rs16Decoder::Classify(std::span<const uint8_t> packet) const {
  if (packet.size() != kPacketBytes) return LidarPacketKind::kUnknown;
  if (HasId(packet, kMsopId)) return LidarPacketKind::kData;
  if (HasId(packet, kDifopId)) return LidarPacketKind::kInfo;
  return LidarPacketKind::kUnknown;
}

int64_t Rs16Decoder::BlockPeriodNs() const {
  return return_mode_ == ReturnMode::kDual ? kFiringPeriodNs : 2 * kFiringPeriodNs;
}

double Rs16Decoder::PacketsPerRevolution() const {
  const double revolution_ns = 60e9 / rpm_;
  return revolution_ns / static_cast<double>(kBlocks * BlockPeriodNs());
}

DecodeStatus Rs16Decoder::DecodeData(std::span<const uint8_t> packet,
                                     std::span<LidarReturn> out,
                                     LidarPacketSummary* summary) const {
  if (packet.size() != kPacketBytes) return DecodeStatus::kWrongSize;
  if (!HasId(packet, kMsopId)) return DecodeStatus::kBadHeader;
  if (out.size() < static_cast<size_t>(kBlocks) * kSlotsPerBlock) {
    return DecodeStatus::kBufferTooSmall;
  }
  const uint8_t* p = packet.data();
  std::array<int, kBlocks> az{};
  int64_t t_packet_ns = 0;
  if (!ReadBlockAzimuths(p, &az) ||
      !ParseTime(p + kTimeOffset, options_.time_format, &t_packet_ns)) {
    return DecodeStatus::kBadHeader;
  }
  const int64_t block_ns = BlockPeriodNs();
  // Nominal azimuth step per block, 0.01°: rpm·360/60 °/s × block period.
  const double nominal_step = rpm_ * 6.0 * static_cast<double>(block_ns) * 1e-9 * 100.0;
  std::array<double, kBlocks> step{};
  BlockSteps(az, nominal_step, &step);

  uint32_t n = 0;
  uint32_t no_returns = 0;
  for (int b = 0; b < kBlocks; ++b) {
    const auto bi = static_cast<size_t>(b);
    const BlockInput block{p + kFirstBlockOffset + bi * kBlockBytes + 4, b, az[bi], step[bi],
                           t_packet_ns + b * block_ns};
    n += DecodeBlock(block, out.data() + n, &no_returns);
  }
  summary->t_sensor_ns = t_packet_ns;
  summary->first_azimuth_deg = static_cast<float>(az[0] * kAzimuthResolutionDeg);
  summary->last_azimuth_deg = static_cast<float>(az[kBlocks - 1] * kAzimuthResolutionDeg);
  summary->return_mode = return_mode_;
  summary->returns = n;
  summary->no_returns = no_returns;
  return DecodeStatus::kOk;
}

uint32_t Rs16Decoder::DecodeBlock(const BlockInput& block,
                                  LidarReturn* out,
                                  uint32_t* no_returns) const {
  const bool dual = return_mode_ == ReturnMode::kDual;
  const auto block_ns = static_cast<double>(BlockPeriodNs());
  const double a0 = block.azimuth_cdeg * kCdegToRad;
  const double sa0 = std::sin(a0), ca0 = std::cos(a0);
  uint32_t n = 0;
  for (int s = 0; s < kSlotsPerBlock; ++s) {
    const uint8_t* slot = block.slots + static_cast<size_t>(s) * kSlotBytes;
    const uint16_t raw = bytes::ReadU16Be(slot);
    if (raw == kNoReturnZero || raw == kNoReturnMax || raw < min_raw_ || raw > max_raw_) {
      ++*no_returns;
      continue;
    }
    const auto laser = static_cast<size_t>(s % kLasers);
    const int second = s / kLasers;  // second firing (single) or second return (dual)
    const int64_t offset_ns =
        static_cast<int64_t>(laser) * kLaserSpacingNs + (dual ? 0 : second * kFiringPeriodNs);
    // Interpolated azimuth offset δ (< ~2°): sin/cos by 4th/3rd-order Taylor, error < 1e-8.
    const double delta_cdeg = block.step_cdeg * static_cast<double>(offset_ns) / block_ns;
    const double d = delta_cdeg * kCdegToRad, d2 = d * d;
    const double cd = 1.0 - 0.5 * d2 + d2 * d2 / 24.0, sd = d * (1.0 - d2 / 6.0);
    const double s1 = sa0 * cd + ca0 * sd, c1 = ca0 * cd - sa0 * sd;
    const double sa = s1 * cos_horiz_[laser] + c1 * sin_horiz_[laser];
    const double ca = c1 * cos_horiz_[laser] - s1 * sin_horiz_[laser];
    const double r = raw * resolution_m_;
    const double r_xy = r * cos_vert_[laser];
    LidarReturn& ret = out[n++];
    // rs_driver's frame and formula (rs16_decoder.h): the lens term on the uncalibrated α.
    ret.x_m = static_cast<float>(r_xy * ca + options_.lens_offset_m * c1);
    ret.y_m = static_cast<float>(-(r_xy * sa + options_.lens_offset_m * s1));
    ret.z_m = static_cast<float>(r * sin_vert_[laser] + kLensRzM);
    ret.range_m = static_cast<float>(r);
    double azimuth_deg =
        (block.azimuth_cdeg + delta_cdeg) * kAzimuthResolutionDeg + horizontal_deg_[laser];
    azimuth_deg -= 360.0 * std::floor(azimuth_deg / 360.0);
    ret.azimuth_deg = azimuth_deg >= 360.0 ? 0.0f : static_cast<float>(azimuth_deg);
    ret.intensity = slot[2];
    ret.ring = ring_[laser];
    ret.return_index = static_cast<uint8_t>(dual ? second : 0);
    ret.slot = static_cast<uint16_t>(block.index * kSlotsPerBlock + s);
    ret.t_sensor_ns = block.t_ns + offset_ns;
  }
  return n;
}

DecodeStatus Rs16Decoder::DecodeInfo(std::span<const uint8_t> packet) {
  Rs16DifopInfo info;
  const DecodeStatus status = ParseRs16Difop(packet, &info);
  if (status != DecodeStatus::kOk) return status;
  if (info.damaged_vertical_calibration) return DecodeStatus::kImplausible;
  if (info.has_vertical_calibration) {
    for (size_t c = 0; c < info.vertical_angles_deg.size(); ++c) {
      const double off = std::abs(info.vertical_angles_deg[c] - configured_vertical_deg_[c]);
      if (!(off <= kMaxCalibrationDeviationDeg)) return DecodeStatus::kImplausible;
    }
  }
  if (info.rpm >= 60.0 && info.rpm <= 2400.0) rpm_ = info.rpm;
  if (info.return_mode != ReturnMode::kUnknown) return_mode_ = info.return_mode;
  if (options_.distance_resolution_m <= 0.0 && info.distance_resolution_m != resolution_m_) {
    SetResolution(info.distance_resolution_m);
  }
  if (info.has_vertical_calibration && info.vertical_angles_deg != vertical_deg_) {
    vertical_deg_ = info.vertical_angles_deg;
    UpdateLaserTables();
  }
  difop_ = info;
  has_difop_ = true;
  return DecodeStatus::kOk;
}

}  // namespace swlio::drivers

#pragma once
/// @file
/// RS-LiDAR-16 MSOP/DIFOP decoder (layout and sources in rs16_protocol.h).
///
/// Geometry per return, as RoboSense's rs_driver computes it (decoder_RS16.hpp L316–318 @
/// 4eeadac), in its frame (x forward at azimuth 0, y left, z up; see rs16_protocol.h):
///   x = r·cos ω·cos α_f + L·cos α,   y = −r·cos ω·sin α_f − L·sin α,   z = r·sin ω + RZ,
/// with ω the laser's vertical angle, α the firing's interpolated azimuth, α_f = α + the laser's
/// horizontal calibration (0 for RS16) and L the lens offset (rs16::kLensRxM by default).
/// Deliberate differences from rs_driver, each below 1 cm + 0.025 % of range on the real
/// capture (tests/drivers/rs16_vendor_geometry_test.cpp): doubles instead of its 0.01° integer
/// angles and float tables; DIFOP elevations at their full 0.0001°; the last block's step is
/// the previous measured one, not the nominal one.
/// Single return (strongest or last): a block holds two firing sequences of 55.5 µs
/// (slots 0–15, then 16–31); dual return: one firing sequence, slots 16–31 are the second return
/// (rs_driver Rs16SingleReturnBlockIterator / Rs16DualReturnBlockIterator). Each slot's azimuth
/// is interpolated between its block's azimuth and the next block's by its firing time; the
/// last block reuses the step before it, and a step above twice the nominal one (a jump, e.g.
/// the FOV edge) is replaced by the nominal step from the motor speed.

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "swlio/drivers/lidar_config.h"
#include "swlio/drivers/lidar_decoder.h"
#include "swlio/drivers/rs16_protocol.h"

namespace swlio::drivers {

/// Everything a DIFOP packet tells about the unit.
struct Rs16DifopInfo {
  double rpm = 0.0;  ///< motor speed as reported (0 on some units while spinning up)
  std::array<uint8_t, 4> lidar_ip{};
  std::array<uint8_t, 4> host_ip{};
  std::array<uint8_t, 6> mac{};
  uint16_t msop_src_port = 0;   ///< port the LiDAR sends MSOP from
  uint16_t msop_dst_port = 0;   ///< port the host receives MSOP on
  uint16_t difop_src_port = 0;  ///< port the LiDAR sends DIFOP from
  uint16_t difop_dst_port = 0;  ///< port the host receives DIFOP on
  double fov_start_deg = 0.0;
  double fov_end_deg = 0.0;
  std::array<uint8_t, 5> top_firmware{};
  std::array<uint8_t, 5> bottom_firmware{};
  /// 0.005 m, or 0.01 m for the old top-board firmware listed in rs16_protocol.h.
  double distance_resolution_m = rs16::kDistanceResolutionM;
  /// Bottom firmware ≥ 08 02 09; older units send strongest return whatever byte 300 says.
  bool supports_dual_return = false;
  ReturnMode return_mode = ReturnMode::kUnknown;  ///< kStrongest when !supports_dual_return
  bool time_valid = false;
  int64_t t_sensor_ns = 0;  ///< DIFOP header time (YMD), sensor clock
  /// false when pitch_cali is blank (all 0x00/0xFF, as rs_driver checks) or damaged.
  bool has_vertical_calibration = false;
  bool damaged_vertical_calibration = false;     ///< not blank, but an angle beyond 90°
  std::array<double, 16> vertical_angles_deg{};  ///< by laser channel as transmitted, not ring
};

/// Parses a DIFOP packet. Returns kWrongSize / kBadHeader without touching `info`.
DecodeStatus ParseRs16Difop(std::span<const uint8_t> packet, Rs16DifopInfo* info);

struct Rs16DecoderOptions {
  rs16::TimeFormat time_format = rs16::TimeFormat::kAuto;
  /// Used until a DIFOP packet reports the unit's return mode.
  ReturnMode initial_return_mode = ReturnMode::kStrongest;
  /// Metres per distance code: 0 = 5 mm until a DIFOP names old (10 mm) firmware; else fixed.
  double distance_resolution_m = 0.0;
  /// Horizontal distance of the optical centre from the rotation axis, along the firing's
  /// uncalibrated azimuth: RoboSense's RX for RS16 by default (rs16_protocol.h). 0 gives the
  /// manual's formula (§8.1), 3.8 cm off the vendor's points. `range_m` stays the measured range.
  double lens_offset_m = rs16::kLensRxM;
};

class Rs16Decoder final : public LidarPacketDecoder {
 public:
  /// Uses `config.vertical_angles_deg` (indexed by ring, nominal RS16 channel order assumed),
  /// `config.rpm`, `config.min_range_m` and `config.max_range_m` until a DIFOP supplies more.
  explicit Rs16Decoder(const LidarConfig& config, Rs16DecoderOptions options = {});

  LidarPacketKind Classify(std::span<const uint8_t> packet) const override;
  /// Needs room for every slot (kBlocks × kSlotsPerBlock = 384 returns) in `out`. Rejects the
  /// whole packet (kBadHeader) when a block flag, a block azimuth (≥ 360°) or the header time
  /// is invalid. Distances 0 and 0xFFFF are "no return"; ranges outside [min, max] are dropped;
  /// both are counted in `summary->no_returns`.
  DecodeStatus DecodeData(std::span<const uint8_t> packet,
                          std::span<LidarReturn> out,
                          LidarPacketSummary* summary) const override;
  /// Adopts rpm (when in 60…2400), return mode, distance resolution (unless fixed by the
  /// options) and vertical calibration (when present). A calibration with an angle beyond 90°
  /// or more than kMaxCalibrationDeviationDeg from the configured one is damaged content: the
  /// packet is refused (kImplausible) and nothing of it adopted.
  DecodeStatus DecodeInfo(std::span<const uint8_t> packet) override;
  /// Factory calibrations differ from the nominal RS16 angles by hundredths of a degree
  /// (RoboSense's example angle.csv: at most 0.04°); one wrong bit in the 3-byte field moves an
  /// angle by 0.0001° · 2^k, so beyond 1° the field is damaged, not calibrated.
  static constexpr double kMaxCalibrationDeviationDeg = 1.0;
  double PacketsPerRevolution() const override;
  double Rpm() const override { return rpm_; }
  std::string Model() const override { return "rs16"; }

  /// Replaces the per-channel calibration (degrees, by laser channel as transmitted).
  void SetCalibration(const std::array<double, 16>& vertical_deg_by_channel,
                      const std::array<double, 16>& horizontal_deg_by_channel);

  bool has_difop() const { return has_difop_; }
  const Rs16DifopInfo& difop() const { return difop_; }
  ReturnMode return_mode() const { return return_mode_; }
  const std::array<double, 16>& vertical_deg_by_channel() const { return vertical_deg_; }
  /// Ring (0 = lowest elevation) of each laser channel.
  const std::array<uint16_t, 16>& ring_of_channel() const { return ring_; }
  double distance_resolution_m() const { return resolution_m_; }
  /// Duration of one block: 111 µs in single-return mode, 55.5 µs in dual.
  int64_t BlockPeriodNs() const;

 private:
  struct BlockInput {
    const uint8_t* slots;  ///< first of the block's 32 three-byte slots
    int index;             ///< block number in the packet, 0–11
    int azimuth_cdeg;      ///< block azimuth, 0.01°
    double step_cdeg;      ///< azimuth advance over one block period, 0.01°
    int64_t t_ns;          ///< time of the block's first firing, sensor clock
  };
  /// Decodes one block's valid slots into `out`; returns how many were written.
  uint32_t DecodeBlock(const BlockInput& block, LidarReturn* out, uint32_t* no_returns) const;
  void UpdateLaserTables();
  void SetResolution(double resolution_m);

  Rs16DecoderOptions options_;
  double rpm_;
  ReturnMode return_mode_;
  double min_range_m_;
  double max_range_m_;
  double resolution_m_ = rs16::kDistanceResolutionM;
  uint16_t min_raw_ = 1;      ///< smallest accepted distance code (≥ 1)
  uint16_t max_raw_ = 65534;  ///< largest accepted distance code (≤ 0xFFFE)
  bool has_difop_ = false;
  Rs16DifopInfo difop_;
  std::array<double, 16> vertical_deg_{};
  std::array<double, 16> configured_vertical_deg_{};  ///< by channel, from the LidarConfig
  std::array<double, 16> horizontal_deg_{};
  std::array<uint16_t, 16> ring_{};
  std::array<double, 16> cos_vert_{};
  std::array<double, 16> sin_vert_{};
  std::array<double, 16> cos_horiz_{};
  std::array<double, 16> sin_horiz_{};
};

}  // namespace swlio::drivers

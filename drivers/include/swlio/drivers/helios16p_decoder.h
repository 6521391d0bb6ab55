#pragma once
/// @file
/// RoboSense RS-Helios-16P MSOP/DIFOP decoder (see helios16p_decoder.cpp for the wire format).

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "swlio/drivers/lidar_decoder.h"

namespace swlio::drivers {

namespace helios16p {
/// Optical (lens) centre that RoboSense's drivers add along the firing's uncalibrated azimuth,
/// as for RS16 (rs_driver `decoder_RSHELIOS_16P.hpp` `getConstParam` RX 0.03498, RY −0.015,
/// RZ 0 and its formula L245–247 @ 4eeadac; nebula c60082d `robosense_helios16P_decoder.hpp`).
inline constexpr double kLensRxM = 0.03498;
/// Declared beside RX but applied by neither driver's Helios-16P formula, so not here either.
inline constexpr double kLensRyUnusedM = -0.015;
}  // namespace helios16p

/// Per-laser angle calibration of a Helios-16P, in packet laser order (laser i is channel i and
/// i + 16 of a block). Degrees; elevation positive up, horizontal offset positive clockwise seen
/// from above (RoboSense convention, added to the block azimuth).
struct Helios16pCalibration {
  /// Fallback used until a DIFOP packet arrives: the factory calibration of a real Helios-16P,
  /// as published in tier4/nebula `RobosenseHelios16P.csv` (commit c60082d) and sent by that
  /// unit in its DIFOP (lasers 0–15).
  std::array<double, 16> vertical_deg = {14.94, 13.03, 10.92, 8.90,  6.96,  5.46,  3.98,  2.67,
                                         1.33,  0.0,   -1.33, -2.67, -3.96, -5.23, -6.63, -8.01};
  std::array<double, 16> horizontal_deg = {-4.05, 3.61, -4.00, 3.58, -3.97, 3.56, -3.96, 3.55,
                                           -3.95, 3.55, -3.95, 3.55, -3.96, 3.56, -3.97, 3.57};
};

struct Helios16pOptions {
  Helios16pCalibration calibration;  ///< used until DIFOP supplies the unit's own
  double min_range_m = 0.2;          ///< returns below are dropped (rs_driver default 0.1–0.2 m)
  double max_range_m = 180.0;        ///< rs_driver's Helios maximum distance
  double rpm = 600.0;                ///< motor speed until DIFOP reports it
  /// Lens offset along the firing's azimuth (see helios16p::kLensRxM), metres.
  double lens_offset_m = helios16p::kLensRxM;
};

/// Fields of the last DIFOP packet (zeros until one arrives).
struct Helios16pInfo {
  bool difop_seen = false;
  bool calibration_from_difop = false;  ///< false: DIFOP angles were invalid, fallback kept
  uint16_t rpm = 0;
  uint16_t msop_port = 0;
  uint16_t difop_port = 0;
  uint16_t fov_start_cdeg = 0;   ///< 0.01°
  uint16_t fov_end_cdeg = 0;     ///< 0.01°
  uint8_t return_mode_byte = 0;  ///< 0x00 dual, 0x04 strongest, 0x05 last, 0x06 nearest
};

class Helios16pDecoder final : public LidarPacketDecoder {
 public:
  static constexpr size_t kPacketBytes = 1248;

  explicit Helios16pDecoder(const Helios16pOptions& options = {});

  LidarPacketKind Classify(std::span<const uint8_t> packet) const override;
  DecodeStatus DecodeData(std::span<const uint8_t> packet,
                          std::span<LidarReturn> out,
                          LidarPacketSummary* summary) const override;
  DecodeStatus DecodeInfo(std::span<const uint8_t> packet) override;
  double PacketsPerRevolution() const override;
  std::string Model() const override { return "helios16p"; }

  const Helios16pInfo& Info() const { return info_; }
  ReturnMode Mode() const { return mode_; }
  /// Ring (0 = lowest elevation) of packet laser 0–15 under the current calibration.
  uint16_t RingOfLaser(size_t laser) const { return ring_[laser]; }
  /// Current calibration in 0.01° (what the decoder actually uses).
  int32_t VerticalCdeg(size_t laser) const { return vert_cdeg_[laser]; }
  int32_t HorizontalCdeg(size_t laser) const { return horiz_cdeg_[laser]; }

 private:
  void SetCalibration(const std::array<int32_t, 16>& vert_cdeg,
                      const std::array<int32_t, 16>& horiz_cdeg);
  void SetRpm(double rpm);
  void DecodeBlock(const uint8_t* block,
                   int32_t az_step_cdeg,
                   int64_t t_block_ns,
                   std::span<LidarReturn> out,
                   LidarPacketSummary* summary) const;

  Helios16pOptions options_;
  Helios16pInfo info_;
  ReturnMode mode_ = ReturnMode::kStrongest;
  double rpm_ = 600.0;
  int32_t nominal_block_step_cdeg_ = 20;  ///< azimuth advance per block at rpm_
  std::array<int32_t, 16> vert_cdeg_{};
  std::array<int32_t, 16> horiz_cdeg_{};
  std::array<float, 16> sin_vert_{};
  std::array<float, 16> cos_vert_{};
  std::array<uint16_t, 16> ring_{};
};

}  // namespace swlio::drivers

#pragma once
/// @file
/// Velodyne VLP-16 data-packet decoder (see vlp16_decoder.cpp for the wire format).

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "swlio/drivers/lidar_decoder.h"

namespace swlio::drivers {

struct Vlp16Options {
  double min_range_m = 0.3;    ///< returns below are dropped (VLP-16 manual: min range ~0.5 m)
  double max_range_m = 130.0;  ///< largest encodable range is 131.07 m
  double rpm = 600.0;          ///< for PacketsPerRevolution only (the VLP-16 sends no DIFOP)
  bool dual_return = false;    ///< expected mode, for PacketsPerRevolution only
  /// Offset of the optical centre along the firing's azimuth, metres, added as for the
  /// RoboSense models. 0: Velodyne's drivers add none (velodyne VLP16db.yaml and nebula's
  /// VLP16.yaml have every offset correction 0).
  double lens_offset_m = 0.0;
};

/// Decodes VLP-16 data packets (1206 bytes, UDP 2368). Velodyne sends no DIFOP on the data port,
/// so DecodeInfo always reports kBadHeader; the return mode comes from each packet.
///
/// Dual-return packets carry block pairs: the first block of a pair holds the last return
/// (`return_index` 0), the second the strongest, or the second strongest when the last is also
/// the strongest (`return_index` 1). A second return equal in distance to the first is a
/// duplicate and is not emitted (counted in neither `returns` nor `no_returns`).
class Vlp16Decoder final : public LidarPacketDecoder {
 public:
  static constexpr size_t kPacketBytes = 1206;

  explicit Vlp16Decoder(const Vlp16Options& options = {});

  LidarPacketKind Classify(std::span<const uint8_t> packet) const override;
  DecodeStatus DecodeData(std::span<const uint8_t> packet,
                          std::span<LidarReturn> out,
                          LidarPacketSummary* summary) const override;
  DecodeStatus DecodeInfo(std::span<const uint8_t> packet) override;
  double PacketsPerRevolution() const override;
  std::string Model() const override { return "vlp16"; }

  /// Elevation of laser id 0–15 from the VLP-16 manual, degrees.
  static double ElevationDeg(size_t laser);
  /// Ring (0 = lowest elevation) of laser id 0–15.
  static uint16_t RingOfLaser(size_t laser);

 private:
  void DecodeBlock(const uint8_t* packet,
                   size_t block,
                   bool dual,
                   float step_cdeg,
                   int64_t t_packet_ns,
                   std::span<LidarReturn> out,
                   LidarPacketSummary* s) const;

  Vlp16Options options_;
  std::array<float, 16> sin_vert_{};
  std::array<float, 16> cos_vert_{};
};

}  // namespace swlio::drivers

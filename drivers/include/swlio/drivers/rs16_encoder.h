#pragma once
/// @file
/// RS-LiDAR-16 MSOP/DIFOP encoder, the inverse of Rs16Decoder (layout in rs16_protocol.h), for
/// the simulator and round-trip tests. Quantization: distance 5 mm (rounded to nearest),
/// azimuth 0.01°, vertical calibration 0.0001°, time 1 µs (truncated).

#include <array>
#include <cstdint>
#include <span>

#include "swlio/drivers/lidar_decoder.h"
#include "swlio/drivers/rs16_protocol.h"

namespace swlio::drivers {

/// One MSOP block: azimuth of its first firing and 32 slots (see rs16_decoder.h for the slot
/// order). A range of 0 (or below 5 mm) encodes "no return" (distance code 0).
struct Rs16BlockContent {
  double azimuth_deg = 0.0;  ///< wrapped into [0, 360)
  std::array<float, 32> range_m{};
  std::array<uint8_t, 32> intensity{};
};

struct Rs16MsopContent {
  int64_t t_sensor_ns = 0;  ///< time of the first firing, sensor clock
  rs16::TimeFormat time_format = rs16::TimeFormat::kYmd;
  uint8_t lidar_type = 0x01;  ///< header byte 30 as sent by the real unit
  double distance_resolution_m = rs16::kDistanceResolutionM;  ///< 0.01 for old firmware
  std::array<Rs16BlockContent, 12> blocks{};
};

/// Fills slots from decoded (or simulated) returns, which must carry `slot`, `range_m` and
/// `intensity`; block azimuths are not touched. Returns the number of returns used (those with
/// a slot < 384).
size_t FillRs16Slots(std::span<const LidarReturn> returns, Rs16MsopContent* content);

/// The range to encode for a point given in the decoder's frame (metres), for simulators that
/// produce points: the distance from the lens centre, |p − L·(cos α, −sin α, 0)|, α being the
/// firing's uncalibrated azimuth and L the lens offset the decoder will add (rs16_decoder.h).
float RangeOfPoint(
    float x_m, float y_m, float z_m, double azimuth_deg, double lens_offset_m = rs16::kLensRxM);

/// Writes one 1248-byte MSOP packet. Returns false when `out` is not 1248 bytes or the time
/// cannot be represented in the chosen format.
bool EncodeRs16Msop(const Rs16MsopContent& content, std::span<uint8_t> out);

struct Rs16DifopContent {
  uint16_t rpm = 600;
  std::array<uint8_t, 4> lidar_ip = {192, 168, 1, 200};
  std::array<uint8_t, 4> host_ip = {192, 168, 1, 102};
  std::array<uint8_t, 6> mac = {0x40, 0x2C, 0x76, 0x00, 0x00, 0x01};
  uint16_t msop_port = 6699;   ///< written as both source and destination MSOP port
  uint16_t difop_port = 7788;  ///< written as both source and destination DIFOP port
  double fov_start_deg = 0.0;
  double fov_end_deg = 360.0;
  ReturnMode return_mode = ReturnMode::kStrongest;
  /// Firmware versions as the real unit in shared/data sends them (5 mm, dual-capable).
  std::array<uint8_t, 5> top_firmware = {0x06, 0x30, 0x00, 0x54, 0x00};
  std::array<uint8_t, 5> bottom_firmware = {0x09, 0x00, 0x0C, 0x02, 0xA0};
  int64_t t_sensor_ns = 0;  ///< DIFOP time (YMD); before 2000 writes a zero time
  /// By laser channel as transmitted; channels 0–7 must be ≤ 0 and 8–15 ≥ 0 (the wire format
  /// carries only magnitudes).
  std::array<double, 16> vertical_angles_deg = {-15, -13, -11, -9, -7, -5, -3, -1,
                                                15,  13,  11,  9,  7,  5,  3,  1};
};

/// Writes one 1248-byte DIFOP packet. Returns false when `out` is not 1248 bytes or an angle
/// has the wrong sign for its channel or exceeds 90°.
bool EncodeRs16Difop(const Rs16DifopContent& content, std::span<uint8_t> out);

}  // namespace swlio::drivers

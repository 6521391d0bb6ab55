#pragma once
/// @file
/// The interface every LiDAR packet decoder implements (RS-LiDAR-16, RS-Helios-16P, VLP-16).
///
/// A decoder is pure: bytes in, returns out, no I/O and no allocation per packet (the caller
/// owns a fixed-size output buffer). Data packets (RoboSense MSOP, Velodyne data) yield returns;
/// info packets (RoboSense DIFOP, Velodyne has none on the data port) update the calibration the
/// decoder uses. Scan assembly (cut angle, gaps, partial scans) happens after decoding.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace swlio::drivers {

/// One return decoded from a data packet, before scan assembly.
/// Frame: the one the vendor's own ROS driver publishes (REP 103): x forward (azimuth 0), y left,
/// z up, azimuth growing clockwise seen from above. RoboSense rs_driver / rslidar_sdk
/// (`decoder_RS16.hpp` L316–318 @ 4eeadac) and ros-drivers/velodyne (`rawdata.cc` "Use standard
/// ROS coordinate system", L800–802 @ 29abd0e) both give x = r·cos ω·cos α, y = −r·cos ω·sin α,
/// z = r·sin ω, plus RoboSense's lens offset along α. (The vendors' manuals draw y forward and
/// x right instead: x_manual = −y, y_manual = x.) An extrinsic calibrated against those drivers'
/// clouds applies to these points unchanged.
struct LidarReturn {
  float x_m = 0.0f;
  float y_m = 0.0f;
  float z_m = 0.0f;
  float range_m = 0.0f;
  float azimuth_deg = 0.0f;  ///< horizontal angle of this firing (after calibration), [0, 360)
  float intensity = 0.0f;    ///< reflectivity as reported, 0–255
  uint16_t ring = 0;         ///< laser channel sorted by elevation, 0 = lowest
  /// 0: the only return, or the first of a dual pair in packet order (RS16/Helios: strongest
  /// or first as rs_driver lays them out; VLP-16: last); 1: the second of a dual pair.
  uint8_t return_index = 0;
  uint16_t slot = 0;  ///< position in its packet: block × slots-per-block + slot (for encoders)
  /// Firing time on the sensor's own clock, ns (header time + firing offset). Not host time:
  /// the clock model maps it. May wrap (VLP-16: µs past the hour).
  int64_t t_sensor_ns = 0;
};

enum class LidarPacketKind : uint8_t { kData, kInfo, kUnknown };
enum class ReturnMode : uint8_t { kStrongest, kLast, kDual, kUnknown };

/// What one data packet held, besides its returns.
struct LidarPacketSummary {
  int64_t t_sensor_ns = 0;         ///< packet time on the sensor clock
  float first_azimuth_deg = 0.0f;  ///< azimuth of the packet's first block
  float last_azimuth_deg = 0.0f;   ///< azimuth of the packet's last block
  ReturnMode return_mode = ReturnMode::kUnknown;
  uint32_t returns = 0;     ///< returns written (valid ranges only)
  uint32_t no_returns = 0;  ///< channel slots with "no return" / out-of-range values
};

enum class DecodeStatus : uint8_t {
  kOk,
  kWrongSize,       ///< packet length is not the format's
  kBadHeader,       ///< magic bytes / block flags do not match
  kBufferTooSmall,  ///< caller's output buffer cannot hold the packet's returns
  kImplausible,     ///< well formed, but values the sensor cannot send (damaged content)
};

class LidarPacketDecoder {
 public:
  /// Enough for any supported format (12 blocks × 32 slots × 2 returns).
  static constexpr size_t kMaxReturnsPerPacket = 768;
  using ReturnBuffer = std::array<LidarReturn, kMaxReturnsPerPacket>;

  virtual ~LidarPacketDecoder() = default;

  /// Which kind of packet this is, from its length and magic bytes only.
  virtual LidarPacketKind Classify(std::span<const uint8_t> packet) const = 0;

  /// Decodes a data packet. Writes `summary->returns` entries to `out`.
  virtual DecodeStatus DecodeData(std::span<const uint8_t> packet,
                                  std::span<LidarReturn> out,
                                  LidarPacketSummary* summary) const = 0;

  /// Decodes an info packet and adopts its calibration (angles, rpm, ports, return mode).
  virtual DecodeStatus DecodeInfo(std::span<const uint8_t> packet) = 0;

  /// Nominal number of data packets per revolution at the current rpm and return mode.
  virtual double PacketsPerRevolution() const = 0;

  /// Motor speed the decoder currently assumes (config, then info packets), rpm; 0 if unknown.
  /// Added for the scan assembler's time-based gap detection; the default keeps older decoders
  /// compiling.
  virtual double Rpm() const { return 0.0; }

  /// Model name ("rs16", "helios16p", "vlp16").
  virtual std::string Model() const = 0;
};

}  // namespace swlio::drivers

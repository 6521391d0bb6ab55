#pragma once
/// @file
/// RS-LiDAR-16 wire format: offsets and constants shared by the decoder and the encoder.
///
/// Sources: RoboSense rs_driver `src/rs_driver/driver/decoder/decoder_RS16.hpp` (packet layout
/// `RS16MsopPkt`/`RS16DifopPkt`, ids, 0.005 m distance resolution, firing times 0…42 µs in
/// 2.8 µs steps plus 55.5 µs for the second firing, pitch_cali as 16 × 24-bit big-endian values
/// in 0.0001°, negative for channels 0–7, return-mode byte 0 dual / 1 strongest / 2 last),
/// rs_driver `basic_attr.hpp` (`RSMsopHeaderV1`, `RSEthNetV1`, `RSTimestampYMD`,
/// `RSTimestampUTC`), and the RS-LiDAR-16 User Manual (§5.1.1 header: bytes 21–30 time, 31
/// model, tail 4 reserved + 00 FF; App. B.7 pitch example 00 27 10 → 1°; App. B.10 time).
/// Every offset below was checked against the real capture in shared/data/rs16_washing_house.
///
/// Point frame: the one RoboSense's drivers publish (rs_driver `decoder_RS16.hpp`
/// `internDecodeMsopPkt`, commit 4eeadac L316–318; rslidar_sdk clouds): x forward (azimuth 0),
/// y left, z up, azimuth clockwise seen from above. The manual's §8.1 formula is the same rays
/// with x and y swapped (x_manual = −y, y_manual = x), as its Note 1 says of the ROS package.
///
/// MSOP (1248 B, all fields big-endian):
///   0   8  id 55 AA 05 0A 5A A5 50 A0
///   20 10  time: YMD (year−2000, month, day, hour, min, s, ms u16, µs u16) or, on newer
///          firmware, UTC (seconds u48, µs u32)
///   30  1  lidar type;  38 2 temperature
///   42 + 100·b  block b (0…11): FF EE, azimuth u16 in 0.01°, 32 × {distance u16, intensity u8}
///   1242 4  packet index (unused here); 1246 2 tail 00 FF
/// DIFOP (1248 B): 0 id A5 FF 00 5A 11 11 55 55; 8 rpm u16; 10 lidar IP; 14 host IP; 18 MAC;
///   24/26 MSOP source/destination port; 28/30 DIFOP source/destination port; 32/34 FOV start/end
///   (0.01°); 40 top-board firmware 5 B; 45 bottom-board firmware 5 B; 300 return mode (honoured
///   only when the bottom firmware is ≥ 08 02 09, ros_rslidar processDifop); 303 time (YMD);
///   1165 pitch_cali 48 B.

#include <array>
#include <cstddef>
#include <cstdint>

namespace swlio::drivers::rs16 {

inline constexpr size_t kPacketBytes = 1248;
inline constexpr std::array<uint8_t, 8> kMsopId = {0x55, 0xAA, 0x05, 0x0A, 0x5A, 0xA5, 0x50, 0xA0};
inline constexpr std::array<uint8_t, 8> kDifopId = {0xA5, 0xFF, 0x00, 0x5A, 0x11, 0x11, 0x55, 0x55};
inline constexpr uint8_t kBlockFlag0 = 0xFF;
inline constexpr uint8_t kBlockFlag1 = 0xEE;

inline constexpr int kLasers = 16;
inline constexpr int kBlocks = 12;
inline constexpr int kSlotsPerBlock = 32;  ///< 2 firings × 16 lasers (dual: 2 returns × 16)
inline constexpr size_t kTimeOffset = 20;
inline constexpr size_t kLidarTypeOffset = 30;
inline constexpr size_t kFirstBlockOffset = 42;
inline constexpr size_t kBlockBytes = 100;
inline constexpr size_t kSlotBytes = 3;
inline constexpr size_t kTailOffset = 1242;

/// Distance per code: 5 mm (rs_driver RS16 DISTANCE_RES); units whose top-board firmware
/// (DIFOP bytes 41–43) reads 00 00 00, FF FF FF, 55 AA 5A or E9 01 00 use 10 mm (RoboSense
/// ros_rslidar rawdata.cc processDifop, "dis_resolution_mode").
inline constexpr double kDistanceResolutionM = 0.005;
inline constexpr double kOldDistanceResolutionM = 0.01;
inline constexpr double kAzimuthResolutionDeg = 0.01;
/// Optical (lens) centre that RoboSense's drivers add to every point, along the firing's
/// uncalibrated azimuth α: (RX cos α, −RX sin α, RZ) (rs_driver `decoder_RS16.hpp`
/// `getConstParam` RX/RY/RZ and L316–318 @ 4eeadac; ros_rslidar `rawdata.cc` Rx_/Ry_/Rz_).
inline constexpr double kLensRxM = 0.03825;
inline constexpr double kLensRzM = 0.0;
/// Declared by RoboSense beside RX but applied by none of its RS16 formulas (ros_rslidar
/// `rawdata.h`: "for now not used"; rs_driver reads RY only for RSAIRY/RSFAIRY), so not here
/// either: a vendor-exact point has no sideways lens term.
inline constexpr double kLensRyUnusedM = -0.01088;
inline constexpr uint16_t kNoReturnZero = 0x0000;
inline constexpr uint16_t kNoReturnMax = 0xFFFF;

/// One firing sequence of all 16 lasers: 55.5 µs; laser k fires 2.8·k µs after its start.
inline constexpr int64_t kFiringPeriodNs = 55'500;
inline constexpr int64_t kLaserSpacingNs = 2'800;

inline constexpr size_t kDifopRpm = 8;
inline constexpr size_t kDifopLidarIp = 10;
inline constexpr size_t kDifopHostIp = 14;
inline constexpr size_t kDifopMac = 18;
inline constexpr size_t kDifopMsopSrcPort = 24;
inline constexpr size_t kDifopMsopDstPort = 26;
inline constexpr size_t kDifopDifopSrcPort = 28;
inline constexpr size_t kDifopDifopDstPort = 30;
inline constexpr size_t kDifopFovStart = 32;
inline constexpr size_t kDifopFovEnd = 34;
inline constexpr size_t kDifopTopFirmware = 40;     ///< 5 bytes
inline constexpr size_t kDifopBottomFirmware = 45;  ///< 5 bytes
inline constexpr size_t kDifopReturnMode = 300;
inline constexpr size_t kDifopTime = 303;
inline constexpr size_t kDifopPitchCali = 1165;
inline constexpr double kPitchCaliResolutionDeg = 0.0001;
inline constexpr uint8_t kReturnModeDual = 0x00;
inline constexpr uint8_t kReturnModeStrongest = 0x01;
inline constexpr uint8_t kReturnModeLast = 0x02;

/// Nominal RS16 layout (User Manual, "vertical angle of each channel"): channels 0–7 point
/// −15°…−1°, channels 8–15 point +15°…+1°. Ring (0 = lowest) of each channel at these angles.
inline constexpr std::array<uint16_t, 16> kNominalRingOfChannel = {0,  1,  2,  3,  4,  5,  6, 7,
                                                                   15, 14, 13, 12, 11, 10, 9, 8};

/// Which header time layout a packet uses.
enum class TimeFormat : uint8_t {
  kAuto,  ///< UTC when bytes 20–21 are zero (a YMD month is never 0), else YMD
  kYmd,   ///< year/month/day/hour/min/s/ms/µs (rs_driver RSTimestampYMD)
  kUtc,   ///< 48-bit seconds + 32-bit µs (rs_driver RSTimestampUTC)
};

}  // namespace swlio::drivers::rs16

namespace swlio::drivers::rs16 {

/// Reads the 10-byte header time at `p` as ns since the Unix epoch (UTC; YMD years are
/// 2000 + year byte). Returns false when a field is out of range (month 13, µs ≥ 1000, …).
bool ParseTime(const uint8_t* p, TimeFormat format, int64_t* t_ns);

/// Writes `t_ns` (≥ 2000-01-01 for YMD, ≥ 0 for UTC) in `format` (kAuto writes YMD).
/// Sub-µs digits are truncated. Returns false when the time cannot be represented.
bool WriteTime(uint8_t* p, TimeFormat format, int64_t t_ns);

}  // namespace swlio::drivers::rs16

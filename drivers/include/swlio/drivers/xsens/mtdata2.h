#pragma once
/// @file
/// MTData2 (Xbus MID 0x36) items: typed sample, pure decoder, encoder, ImuSample conversion.
///
/// Protocol summary (Xsens MT0101P "MT Low Level Communication Protocol Documentation",
/// section "MTData2" and the "Data identifiers" table, XDI values as in Xsens'
/// XsDataIdentifier list):
/// - The payload is a sequence of items: XDI (2 bytes, big-endian), size (1 byte), data.
/// - XDI & 0xFFF0 is the data type; bits 0–1 the precision of real values (0 Float32,
///   1 FP12.20, 2 FP16.32, 3 Float64); bits 2–3 the coordinate system (0 ENU, 1 NED, 2 NWU).
/// - FP12.20: signed 32-bit integer / 2^20. FP16.32: 6 bytes, the 32-bit fractional part
///   first, then the signed 16-bit integer part (Xsens article "An explanation of the MTi
///   fixed point output formats"; byte order confirmed on the einride FP16.32 capture).
/// - All values big-endian. Units: m/s², rad/s, m/s, degrees, arbitrary units (magnetic
///   field, normalized to the local field), °C, Pa; SampleTimeFine counts 10 kHz ticks.
/// GNSS PVT and satellite info follow u-blox NAV-PVT / NAV-SAT field order (MT0101P tables
/// "Contents of GnssPvtData" and "GnssSatInfo").

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "swlio/core/types.h"

namespace swlio::drivers::xsens {

/// Data identifiers (type part, low nibble zero).
namespace xdi {
inline constexpr uint16_t kTemperature = 0x0810;
inline constexpr uint16_t kUtcTime = 0x1010;
inline constexpr uint16_t kPacketCounter = 0x1020;
inline constexpr uint16_t kSampleTimeFine = 0x1060;
inline constexpr uint16_t kSampleTimeCoarse = 0x1070;
inline constexpr uint16_t kQuaternion = 0x2010;
inline constexpr uint16_t kRotationMatrix = 0x2020;
inline constexpr uint16_t kEulerAngles = 0x2030;
inline constexpr uint16_t kBaroPressure = 0x3010;
inline constexpr uint16_t kDeltaV = 0x4010;
inline constexpr uint16_t kAcceleration = 0x4020;
inline constexpr uint16_t kFreeAcceleration = 0x4030;
inline constexpr uint16_t kAccelerationHr = 0x4040;
inline constexpr uint16_t kAltitudeEllipsoid = 0x5020;
inline constexpr uint16_t kPositionEcef = 0x5030;
inline constexpr uint16_t kLatLon = 0x5040;
inline constexpr uint16_t kGnssPvtData = 0x7010;
inline constexpr uint16_t kGnssSatInfo = 0x7020;
inline constexpr uint16_t kRateOfTurn = 0x8020;
inline constexpr uint16_t kDeltaQ = 0x8030;
inline constexpr uint16_t kRateOfTurnHr = 0x8040;
inline constexpr uint16_t kMagneticField = 0xC020;
inline constexpr uint16_t kVelocityXyz = 0xD010;
inline constexpr uint16_t kStatusByte = 0xE010;
inline constexpr uint16_t kStatusWord = 0xE020;
inline constexpr uint16_t kTypeMask = 0xFFF0;
inline constexpr uint16_t kPrecisionMask = 0x0003;
inline constexpr uint16_t kFrameMask = 0x000C;
}  // namespace xdi

enum class XsensPrecision : uint8_t { kFloat32 = 0, kFp1220 = 1, kFp1632 = 2, kFloat64 = 3 };
enum class XsensFrame : uint8_t { kEnu = 0, kNed = 1, kNwu = 2 };

/// Bytes per value on the wire: 4, 4, 6, 8.
size_t XsensValueSize(XsensPrecision precision);

/// A real-valued item (1 to 9 values) with the precision and frame it was sent in.
struct XsensReal {
  std::array<double, 9> v{};
  uint8_t count = 0;
  XsensPrecision precision = XsensPrecision::kFloat32;
  XsensFrame frame = XsensFrame::kEnu;
  double operator[](size_t i) const { return v[i]; }
};

struct XsensUtcTime {
  uint32_t nanoseconds = 0;
  uint16_t year = 0;
  uint8_t month = 0, day = 0, hour = 0, minute = 0, second = 0;
  uint8_t flags = 0;  ///< validity bits as sent
};

/// GnssPvtData (0x7010), 94 bytes, u-blox NAV-PVT order and units (1e-7 deg, mm, mm/s, ns).
struct XsensGnssPvt {
  uint32_t itow_ms = 0;
  uint16_t year = 0;
  uint8_t month = 0, day = 0, hour = 0, min = 0, sec = 0, valid = 0;
  uint32_t t_acc_ns = 0;
  int32_t nano_ns = 0;
  uint8_t fix_type = 0, flags = 0, num_sv = 0, reserved1 = 0;
  int32_t lon_1e7deg = 0, lat_1e7deg = 0, height_mm = 0, hmsl_mm = 0;
  uint32_t h_acc_mm = 0, v_acc_mm = 0;
  int32_t vel_n_mmps = 0, vel_e_mmps = 0, vel_d_mmps = 0, g_speed_mmps = 0;
  int32_t head_mot_1e5deg = 0;
  uint32_t s_acc_mmps = 0, head_acc_1e5deg = 0;
  int32_t head_veh_1e5deg = 0;
  uint16_t gdop = 0, pdop = 0, tdop = 0, vdop = 0, hdop = 0, ndop = 0, edop = 0;  ///< 0.01
};
inline constexpr size_t kGnssPvtSize = 94;

/// GnssSatInfo (0x7020): 8-byte header then 4 bytes per satellite.
struct XsensGnssSatInfo {
  static constexpr size_t kMaxSats = 64;
  struct Sat {
    uint8_t gnss_id = 0, sv_id = 0, cno_dbhz = 0, flags = 0;
  };
  uint32_t itow_ms = 0;
  uint8_t num_svs = 0;  ///< as announced by the device
  uint8_t res1 = 0, res2 = 0, res3 = 0;
  uint8_t stored = 0;  ///< satellites kept (≤ kMaxSats and ≤ the bytes present)
  std::array<Sat, kMaxSats> sats{};
};

/// One decoded MTData2 message. Absent items stay empty.
struct MtData2Sample {
  static constexpr size_t kMaxItems = 32;

  std::optional<uint16_t> packet_counter;
  std::optional<uint32_t> sample_time_fine;    ///< 10 kHz ticks
  std::optional<uint32_t> sample_time_coarse;  ///< seconds
  std::optional<XsensUtcTime> utc_time;
  std::optional<uint32_t> baro_pressure_pa;
  std::optional<uint8_t> status_byte;
  std::optional<uint32_t> status_word;
  std::optional<XsensGnssPvt> gnss_pvt;
  std::optional<XsensGnssSatInfo> gnss_sat_info;

  std::optional<XsensReal> temperature_degc;
  std::optional<XsensReal> quaternion;       ///< q0 (w), q1, q2, q3
  std::optional<XsensReal> rotation_matrix;  ///< a…i as sent (column-major)
  std::optional<XsensReal> euler_deg;        ///< roll, pitch, yaw
  std::optional<XsensReal> delta_v_mps;
  std::optional<XsensReal> acc_mps2;
  std::optional<XsensReal> free_acc_mps2;
  std::optional<XsensReal> acc_hr_mps2;
  std::optional<XsensReal> altitude_ellipsoid_m;
  std::optional<XsensReal> position_ecef_m;
  std::optional<XsensReal> lat_lon_deg;
  std::optional<XsensReal> rate_of_turn_radps;
  std::optional<XsensReal> delta_q;
  std::optional<XsensReal> rate_of_turn_hr_radps;
  std::optional<XsensReal> mag_au;
  std::optional<XsensReal> velocity_mps;

  /// Full XDIs of the decoded (known, well-sized) items, in message order.
  std::array<uint16_t, kMaxItems> item_ids{};
  uint8_t item_count = 0;
  uint16_t unknown_items = 0;   ///< items skipped by their length (unknown XDI)
  uint16_t bad_size_items = 0;  ///< known XDI with an impossible size, skipped
};

enum class MtData2Status : uint8_t {
  kOk = 0,
  kTruncated,  ///< an item header or its data runs past the payload; items before it kept
};

/// Decodes one MTData2 payload (the Xbus data field). Pure, no allocation.
MtData2Status DecodeMtData2(std::span<const uint8_t> payload, MtData2Sample* sample);

/// Encodes the items of `sample`: in `item_ids` order when item_count > 0 (each item in the
/// precision and frame of its XDI), otherwise every present item in a fixed order. Returns the
/// payload size, or 0 when `out` is too small.
size_t EncodeMtData2(const MtData2Sample& sample, std::span<uint8_t> out);

/// Builds an XsensReal from values (helper for encoders and the simulator).
XsensReal MakeXsensReal(std::span<const double> values,
                        XsensPrecision precision = XsensPrecision::kFloat32,
                        XsensFrame frame = XsensFrame::kEnu);

/// Value of `v` after encoding in `precision` and decoding again (quantization model).
double QuantizeXsens(double v, XsensPrecision precision);

/// SampleTimeFine (10 kHz ticks, wraps at 2^32) → ns of the device clock.
inline int64_t SampleTimeFineToNs(uint32_t ticks) { return static_cast<int64_t>(ticks) * 100'000; }

/// Vector of a frame-flagged item expressed with ENU-convention axes: NED (n,e,d) → (e,n,−d),
/// NWU (n,w,u) → (−w,n,u). Sensor-frame items are converted the same way; whether a firmware
/// applies the coordinate flag to sensor-frame data must be checked on the device.
Eigen::Vector3d XsensVectorToEnu(const XsensReal& item);

/// Acceleration (or AccelerationHR) and RateOfTurn (or RateOfTurnHR) as a core sample stamped
/// with the host receive time; nullopt when either is missing.
std::optional<ImuSample> ToImuSample(const MtData2Sample& sample, int64_t host_t_ns);

/// A usable GnssPvtData item as a fix at host time `host_t_ns`. Units (u-blox NAV-PVT): lat/lon
/// 1e-7 deg, height and accuracies mm. Usable: fixType 2 (2-D), 3 (3-D) or 4 (GNSS + dead
/// reckoning), not 0 (none), 1 (dead reckoning only) or 5 (time only); flags bit 0 (gnssFixOK)
/// set; a position on the Earth (height −2…+50 km); accuracies in (0, 1 km]. Else nullopt.
std::optional<GnssFix> ToGnssFix(const XsensGnssPvt& pvt, int64_t host_t_ns);

}  // namespace swlio::drivers::xsens

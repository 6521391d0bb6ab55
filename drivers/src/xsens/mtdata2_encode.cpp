// MTData2 encoder (simulator, tests): the inverse of mtdata2_decode.cpp, same item layout
// (Xsens MT0101P "MTData2"). Fixed-point values are rounded to nearest and saturated.

#include <algorithm>
#include <cmath>

#include "mtdata2_items.h"
#include "swlio/drivers/bytes.h"
#include "swlio/drivers/xsens/mtdata2.h"

namespace swlio::drivers::xsens {
namespace {

using bytes::WriteU16Be;
using bytes::WriteU32Be;

int64_t RoundSaturate(double v, double scale, int64_t lo, int64_t hi) {
  const double x = std::nearbyint(v * scale);
  if (!(x >= static_cast<double>(lo))) return lo;  // also maps NaN to lo
  if (x >= static_cast<double>(hi)) return hi;
  return static_cast<int64_t>(x);
}

constexpr int64_t kFp1632Max = (int64_t{1} << 47) - 1;

void WriteReal(uint8_t* p, double v, XsensPrecision precision) {
  switch (precision) {
    case XsensPrecision::kFloat32:
      bytes::WriteF32Be(p, static_cast<float>(v));
      return;
    case XsensPrecision::kFp1220:
      WriteU32Be(p, static_cast<uint32_t>(RoundSaturate(v, 1048576.0, INT32_MIN, INT32_MAX)));
      return;
    case XsensPrecision::kFp1632: {
      const int64_t raw = RoundSaturate(v, 4294967296.0, -kFp1632Max - 1, kFp1632Max);
      WriteU32Be(p, static_cast<uint32_t>(raw & 0xFFFFFFFF));
      WriteU16Be(p + 4, static_cast<uint16_t>((raw >> 32) & 0xFFFF));
      return;
    }
    case XsensPrecision::kFloat64:
      bytes::WriteF64Be(p, v);
      return;
  }
}

/// Writes the item header; returns the data pointer or nullptr when it does not fit.
uint8_t* Begin(std::span<uint8_t> out, size_t* pos, uint16_t id, size_t size) {
  if (size > 255 || out.size() - *pos < 3 + size) return nullptr;
  uint8_t* p = out.data() + *pos;
  WriteU16Be(p, id);
  p[2] = static_cast<uint8_t>(size);
  *pos += 3 + size;
  return p + 3;
}

bool PutReal(std::span<uint8_t> out, size_t* pos, uint16_t type, const XsensReal& r) {
  const size_t size = XsensValueSize(r.precision);
  uint8_t* p = Begin(out, pos, internal::RealXdi(type, r), size * r.count);
  if (p == nullptr) return false;
  for (size_t i = 0; i < r.count; ++i) WriteReal(p + i * size, r.v[i], r.precision);
  return true;
}

void WritePvt(uint8_t* p, const XsensGnssPvt& g) {
  WriteU32Be(p, g.itow_ms);
  WriteU16Be(p + 4, g.year);
  const uint8_t small[] = {g.month, g.day, g.hour, g.min, g.sec, g.valid};
  std::copy(std::begin(small), std::end(small), p + 6);
  WriteU32Be(p + 12, g.t_acc_ns);
  WriteU32Be(p + 16, static_cast<uint32_t>(g.nano_ns));
  p[20] = g.fix_type;
  p[21] = g.flags;
  p[22] = g.num_sv;
  p[23] = g.reserved1;
  const uint32_t words[] = {static_cast<uint32_t>(g.lon_1e7deg),
                            static_cast<uint32_t>(g.lat_1e7deg),
                            static_cast<uint32_t>(g.height_mm),
                            static_cast<uint32_t>(g.hmsl_mm),
                            g.h_acc_mm,
                            g.v_acc_mm,
                            static_cast<uint32_t>(g.vel_n_mmps),
                            static_cast<uint32_t>(g.vel_e_mmps),
                            static_cast<uint32_t>(g.vel_d_mmps),
                            static_cast<uint32_t>(g.g_speed_mmps),
                            static_cast<uint32_t>(g.head_mot_1e5deg),
                            g.s_acc_mmps,
                            g.head_acc_1e5deg,
                            static_cast<uint32_t>(g.head_veh_1e5deg)};
  for (size_t i = 0; i < 14; ++i) WriteU32Be(p + 24 + 4 * i, words[i]);
  const uint16_t dops[] = {g.gdop, g.pdop, g.tdop, g.vdop, g.hdop, g.ndop, g.edop};
  for (size_t i = 0; i < 7; ++i) WriteU16Be(p + 80 + 2 * i, dops[i]);
}

bool PutSatInfo(std::span<uint8_t> out, size_t* pos, uint16_t id, const XsensGnssSatInfo& s) {
  uint8_t* p = Begin(out, pos, id, 8 + 4 * size_t{s.stored});
  if (p == nullptr) return false;
  WriteU32Be(p, s.itow_ms);
  p[4] = s.num_svs;
  p[5] = s.res1;
  p[6] = s.res2;
  p[7] = s.res3;
  for (size_t i = 0; i < s.stored; ++i) {
    const auto& sat = s.sats[i];
    const uint8_t b[] = {sat.gnss_id, sat.sv_id, sat.cno_dbhz, sat.flags};
    std::copy(std::begin(b), std::end(b), p + 8 + 4 * i);
  }
  return true;
}

/// Encodes the item of type `type` when present. Returns false only when out of space.
bool PutItem(const MtData2Sample& s, uint16_t id, std::span<uint8_t> out, size_t* pos) {
  const auto type = static_cast<uint16_t>(id & xdi::kTypeMask);
  uint8_t* p = nullptr;
  switch (type) {
    case xdi::kPacketCounter:
      if (!s.packet_counter) return true;
      if ((p = Begin(out, pos, id, 2))) WriteU16Be(p, *s.packet_counter);
      return p != nullptr;
    case xdi::kSampleTimeFine:
    case xdi::kSampleTimeCoarse:
    case xdi::kBaroPressure:
    case xdi::kStatusWord: {
      const std::optional<uint32_t>& v = type == xdi::kSampleTimeFine     ? s.sample_time_fine
                                         : type == xdi::kSampleTimeCoarse ? s.sample_time_coarse
                                         : type == xdi::kBaroPressure     ? s.baro_pressure_pa
                                                                          : s.status_word;
      if (!v) return true;
      if ((p = Begin(out, pos, id, 4))) WriteU32Be(p, *v);
      return p != nullptr;
    }
    case xdi::kStatusByte:
      if (!s.status_byte) return true;
      if ((p = Begin(out, pos, id, 1))) p[0] = *s.status_byte;
      return p != nullptr;
    case xdi::kUtcTime: {
      if (!s.utc_time) return true;
      const XsensUtcTime& t = *s.utc_time;
      if (!(p = Begin(out, pos, id, 12))) return false;
      WriteU32Be(p, t.nanoseconds);
      WriteU16Be(p + 4, t.year);
      const uint8_t b[] = {t.month, t.day, t.hour, t.minute, t.second, t.flags};
      std::copy(std::begin(b), std::end(b), p + 6);
      return true;
    }
    case xdi::kGnssPvtData:
      if (!s.gnss_pvt) return true;
      if ((p = Begin(out, pos, id, kGnssPvtSize))) WritePvt(p, *s.gnss_pvt);
      return p != nullptr;
    case xdi::kGnssSatInfo:
      return !s.gnss_sat_info || PutSatInfo(out, pos, id, *s.gnss_sat_info);
    default:
      break;
  }
  const internal::RealItemDef* def = internal::FindRealItem(type);
  if (def == nullptr || !(s.*(def->field))) return true;
  return PutReal(out, pos, type, *(s.*(def->field)));
}

constexpr uint16_t kCanonicalOrder[] = {
    xdi::kPacketCounter, xdi::kSampleTimeFine,   xdi::kSampleTimeCoarse, xdi::kUtcTime,
    xdi::kStatusByte,    xdi::kStatusWord,       xdi::kTemperature,      xdi::kBaroPressure,
    xdi::kQuaternion,    xdi::kRotationMatrix,   xdi::kEulerAngles,      xdi::kDeltaV,
    xdi::kAcceleration,  xdi::kFreeAcceleration, xdi::kAccelerationHr,   xdi::kRateOfTurn,
    xdi::kDeltaQ,        xdi::kRateOfTurnHr,     xdi::kMagneticField,    xdi::kAltitudeEllipsoid,
    xdi::kPositionEcef,  xdi::kLatLon,           xdi::kVelocityXyz,      xdi::kGnssPvtData,
    xdi::kGnssSatInfo};

}  // namespace

size_t EncodeMtData2(const MtData2Sample& sample, std::span<uint8_t> out) {
  size_t pos = 0;
  if (sample.item_count > 0) {
    for (size_t i = 0; i < sample.item_count; ++i) {
      if (!PutItem(sample, sample.item_ids[i], out, &pos)) return 0;
    }
    return pos;
  }
  for (const uint16_t type : kCanonicalOrder) {
    if (!PutItem(sample, type, out, &pos)) return 0;
  }
  return pos;
}

XsensReal MakeXsensReal(std::span<const double> values,
                        XsensPrecision precision,
                        XsensFrame frame) {
  XsensReal r;
  r.count = static_cast<uint8_t>(std::min(values.size(), r.v.size()));
  std::copy_n(values.begin(), r.count, r.v.begin());
  r.precision = precision;
  r.frame = frame;
  return r;
}

double QuantizeXsens(double v, XsensPrecision precision) {
  switch (precision) {
    case XsensPrecision::kFloat32:
      return static_cast<double>(static_cast<float>(v));
    case XsensPrecision::kFp1220:
      return static_cast<double>(RoundSaturate(v, 1048576.0, INT32_MIN, INT32_MAX)) / 1048576.0;
    case XsensPrecision::kFp1632:
      return static_cast<double>(RoundSaturate(v, 4294967296.0, -kFp1632Max - 1, kFp1632Max)) /
             4294967296.0;
    case XsensPrecision::kFloat64:
      return v;
  }
  return v;
}

}  // namespace swlio::drivers::xsens

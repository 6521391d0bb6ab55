// MTData2 decoder. Item layout, precisions and frames: Xsens MT0101P, "MTData2" and the data
// identifier table (summary in mtdata2.h). Pure and allocation-free: every read is bounded by
// the item size, every unknown or ill-sized item is skipped by its length and counted.

#include <cmath>

#include "mtdata2_items.h"
#include "swlio/drivers/bytes.h"
#include "swlio/drivers/xsens/mtdata2.h"

namespace swlio::drivers::xsens {
namespace {

using bytes::ReadI32Be;
using bytes::ReadU16Be;
using bytes::ReadU32Be;

double ReadReal(const uint8_t* p, XsensPrecision precision) {
  switch (precision) {
    case XsensPrecision::kFloat32:
      return static_cast<double>(bytes::ReadF32Be(p));
    case XsensPrecision::kFp1220:
      return static_cast<double>(ReadI32Be(p)) / 1048576.0;  // 2^20
    case XsensPrecision::kFp1632: {
      // 32-bit fraction first, then the signed 16-bit integer part; 48 bits fit a double.
      const int64_t raw = static_cast<int64_t>(bytes::ReadI16Be(p + 4)) * 4294967296LL +
                          static_cast<int64_t>(ReadU32Be(p));
      return static_cast<double>(raw) / 4294967296.0;  // 2^32
    }
    case XsensPrecision::kFloat64:
      return bytes::ReadF64Be(p);
  }
  return 0.0;
}

bool DecodeReal(uint16_t id, std::span<const uint8_t> data, MtData2Sample* s, bool* known) {
  const internal::RealItemDef* def = internal::FindRealItem(id & xdi::kTypeMask);
  if (def == nullptr) return false;
  *known = true;
  const auto precision = static_cast<XsensPrecision>(id & xdi::kPrecisionMask);
  const uint16_t frame_bits = static_cast<uint16_t>((id & xdi::kFrameMask) >> 2);
  const size_t size = XsensValueSize(precision);
  if (frame_bits > 2 || data.size() != size * def->count) return false;
  XsensReal r;
  r.count = def->count;
  r.precision = precision;
  r.frame = static_cast<XsensFrame>(frame_bits);
  for (size_t i = 0; i < def->count; ++i) r.v[i] = ReadReal(data.data() + i * size, precision);
  s->*(def->field) = r;
  return true;
}

XsensUtcTime ReadUtc(const uint8_t* p) {
  XsensUtcTime t;
  t.nanoseconds = ReadU32Be(p);
  t.year = ReadU16Be(p + 4);
  t.month = p[6];
  t.day = p[7];
  t.hour = p[8];
  t.minute = p[9];
  t.second = p[10];
  t.flags = p[11];
  return t;
}

XsensGnssPvt ReadPvt(const uint8_t* p) {
  XsensGnssPvt g;
  g.itow_ms = ReadU32Be(p);
  g.year = ReadU16Be(p + 4);
  g.month = p[6];
  g.day = p[7];
  g.hour = p[8];
  g.min = p[9];
  g.sec = p[10];
  g.valid = p[11];
  g.t_acc_ns = ReadU32Be(p + 12);
  g.nano_ns = ReadI32Be(p + 16);
  g.fix_type = p[20];
  g.flags = p[21];
  g.num_sv = p[22];
  g.reserved1 = p[23];
  g.lon_1e7deg = ReadI32Be(p + 24);
  g.lat_1e7deg = ReadI32Be(p + 28);
  g.height_mm = ReadI32Be(p + 32);
  g.hmsl_mm = ReadI32Be(p + 36);
  g.h_acc_mm = ReadU32Be(p + 40);
  g.v_acc_mm = ReadU32Be(p + 44);
  g.vel_n_mmps = ReadI32Be(p + 48);
  g.vel_e_mmps = ReadI32Be(p + 52);
  g.vel_d_mmps = ReadI32Be(p + 56);
  g.g_speed_mmps = ReadI32Be(p + 60);
  g.head_mot_1e5deg = ReadI32Be(p + 64);
  g.s_acc_mmps = ReadU32Be(p + 68);
  g.head_acc_1e5deg = ReadU32Be(p + 72);
  g.head_veh_1e5deg = ReadI32Be(p + 76);
  uint16_t* dops[] = {&g.gdop, &g.pdop, &g.tdop, &g.vdop, &g.hdop, &g.ndop, &g.edop};
  for (size_t i = 0; i < 7; ++i) *dops[i] = ReadU16Be(p + 80 + 2 * i);
  return g;
}

bool DecodeSatInfo(std::span<const uint8_t> d, MtData2Sample* s) {
  if (d.size() < 8 || (d.size() - 8) % 4 != 0) return false;
  XsensGnssSatInfo& info = s->gnss_sat_info.emplace();
  info.itow_ms = ReadU32Be(d.data());
  info.num_svs = d[4];
  info.res1 = d[5];
  info.res2 = d[6];
  info.res3 = d[7];
  size_t n = (d.size() - 8) / 4;
  if (n > XsensGnssSatInfo::kMaxSats) n = XsensGnssSatInfo::kMaxSats;
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = d.data() + 8 + 4 * i;
    info.sats[i] = {p[0], p[1], p[2], p[3]};
  }
  info.stored = static_cast<uint8_t>(n);
  return true;
}

/// Decodes a non-real item. Returns true when stored; `*known` tells whether the XDI exists.
bool DecodeFixed(uint16_t id, std::span<const uint8_t> d, MtData2Sample* s, bool* known) {
  *known = true;
  const size_t n = d.size();
  // Format bits mean nothing for these integer items; some firmware sets them anyway (the
  // MTi-300 capture sends BaroPressure as 0x3013), so they are matched on the type alone.
  switch (id & xdi::kTypeMask) {
    case xdi::kPacketCounter:
      if (n != 2) return false;
      s->packet_counter = ReadU16Be(d.data());
      return true;
    case xdi::kSampleTimeFine:
      if (n != 4) return false;
      s->sample_time_fine = ReadU32Be(d.data());
      return true;
    case xdi::kSampleTimeCoarse:
      if (n != 4) return false;
      s->sample_time_coarse = ReadU32Be(d.data());
      return true;
    case xdi::kUtcTime:
      if (n != 12) return false;
      s->utc_time = ReadUtc(d.data());
      return true;
    case xdi::kBaroPressure:
      if (n != 4) return false;
      s->baro_pressure_pa = ReadU32Be(d.data());
      return true;
    case xdi::kStatusByte:
      if (n != 1) return false;
      s->status_byte = d[0];
      return true;
    case xdi::kStatusWord:
      if (n != 4) return false;
      s->status_word = ReadU32Be(d.data());
      return true;
    case xdi::kGnssPvtData:
      if (n != kGnssPvtSize) return false;
      s->gnss_pvt = ReadPvt(d.data());
      return true;
    case xdi::kGnssSatInfo:
      return DecodeSatInfo(d, s);
    default:
      *known = false;
      return false;
  }
}

}  // namespace

size_t XsensValueSize(XsensPrecision precision) {
  switch (precision) {
    case XsensPrecision::kFloat32:
    case XsensPrecision::kFp1220:
      return 4;
    case XsensPrecision::kFp1632:
      return 6;
    case XsensPrecision::kFloat64:
      return 8;
  }
  return 4;
}

MtData2Status DecodeMtData2(std::span<const uint8_t> payload, MtData2Sample* sample) {
  *sample = MtData2Sample{};
  size_t pos = 0;
  while (pos < payload.size()) {
    if (payload.size() - pos < 3) return MtData2Status::kTruncated;
    const uint16_t id = ReadU16Be(payload.data() + pos);
    const size_t size = payload[pos + 2];
    pos += 3;
    if (payload.size() - pos < size) return MtData2Status::kTruncated;
    const std::span<const uint8_t> data = payload.subspan(pos, size);
    pos += size;
    bool known = false;
    const bool stored =
        DecodeFixed(id, data, sample, &known) || (!known && DecodeReal(id, data, sample, &known));
    if (stored) {
      if (sample->item_count < MtData2Sample::kMaxItems) {
        sample->item_ids[sample->item_count++] = id;
      }
    } else if (known) {
      ++sample->bad_size_items;
    } else {
      ++sample->unknown_items;
    }
  }
  return MtData2Status::kOk;
}

Eigen::Vector3d XsensVectorToEnu(const XsensReal& item) {
  Eigen::Vector3d v(item.v[0], item.v[1], item.v[2]);
  switch (item.frame) {
    case XsensFrame::kNed:
      return {v.y(), v.x(), -v.z()};
    case XsensFrame::kNwu:
      return {-v.y(), v.x(), v.z()};
    case XsensFrame::kEnu:
      break;
  }
  return v;
}

std::optional<ImuSample> ToImuSample(const MtData2Sample& sample, int64_t host_t_ns) {
  const std::optional<XsensReal>& acc = sample.acc_mps2 ? sample.acc_mps2 : sample.acc_hr_mps2;
  const std::optional<XsensReal>& gyro =
      sample.rate_of_turn_radps ? sample.rate_of_turn_radps : sample.rate_of_turn_hr_radps;
  if (!acc || !gyro) return std::nullopt;
  ImuSample imu;
  imu.t_ns = host_t_ns;
  imu.acc_mps2 = XsensVectorToEnu(*acc);
  imu.gyro_radps = XsensVectorToEnu(*gyro);
  return imu;
}

std::optional<GnssFix> ToGnssFix(const XsensGnssPvt& p, int64_t host_t_ns) {
  GnssFix f;
  f.t_ns = host_t_ns;
  f.lat_deg = p.lat_1e7deg * 1e-7;
  f.lon_deg = p.lon_1e7deg * 1e-7;
  f.height_m = p.height_mm * 1e-3;
  f.h_acc_m = p.h_acc_mm * 1e-3;
  f.v_acc_m = p.v_acc_mm * 1e-3;
  f.fix_type = p.fix_type;
  f.num_sv = p.num_sv;
  const bool fix = p.fix_type >= 2 && p.fix_type <= 4 && (p.flags & 0x01) != 0;
  const bool place = std::abs(f.lat_deg) <= 90.0 && std::abs(f.lon_deg) <= 180.0 &&
                     f.height_m >= -2e3 && f.height_m <= 5e4;
  const bool accuracy = f.h_acc_m > 0.0 && f.h_acc_m <= 1e3 && f.v_acc_m > 0.0 && f.v_acc_m <= 1e3;
  if (!fix || !place || !accuracy) return std::nullopt;
  return f;
}

}  // namespace swlio::drivers::xsens

// PointCloud2 → Scan with per-point times (point_cloud_points.h).

#include "swlio/drivers/bag/point_cloud_points.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>

#include "swlio/drivers/bag/message_reader.h"
#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag {
namespace {

constexpr double kNsThreshold = 1e15;  // larger "timestamp" values are ns, not s

/// Bytes of one value of a PointField datatype; 0 for an unknown datatype.
size_t TypeBytes(uint8_t datatype) {
  switch (static_cast<PointFieldType>(datatype)) {
    case PointFieldType::kInt8:
    case PointFieldType::kUint8:
      return 1;
    case PointFieldType::kInt16:
    case PointFieldType::kUint16:
      return 2;
    case PointFieldType::kInt32:
    case PointFieldType::kUint32:
    case PointFieldType::kFloat32:
      return 4;
    case PointFieldType::kFloat64:
      return 8;
  }
  return 0;
}

/// A located field: where it is in a point and how to read it.
struct Field {
  uint32_t offset = 0;
  uint8_t datatype = 0;
};

double ReadValue(const uint8_t* p, uint8_t datatype, bool big_endian) {
  const auto u16 = [&] { return big_endian ? bytes::ReadU16Be(p) : bytes::ReadU16Le(p); };
  const auto u32 = [&] { return big_endian ? bytes::ReadU32Be(p) : bytes::ReadU32Le(p); };
  switch (static_cast<PointFieldType>(datatype)) {
    case PointFieldType::kInt8:
      return static_cast<int8_t>(p[0]);
    case PointFieldType::kUint8:
      return p[0];
    case PointFieldType::kInt16:
      return static_cast<int16_t>(u16());
    case PointFieldType::kUint16:
      return u16();
    case PointFieldType::kInt32:
      return static_cast<int32_t>(u32());
    case PointFieldType::kUint32:
      return u32();
    case PointFieldType::kFloat32:
      return std::bit_cast<float>(u32());
    case PointFieldType::kFloat64:
      return big_endian ? bytes::ReadF64Be(p) : bytes::ReadF64Le(p);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// The field called `name`, if it exists and fits in a point of `point_step` bytes.
std::optional<Field> Find(const PointCloud2Msg& msg, std::string_view name, std::string* error) {
  for (const PointFieldView& f : msg.fields) {
    if (f.name != name) continue;
    const size_t n = TypeBytes(f.datatype);
    if (n == 0 || static_cast<uint64_t>(f.offset) + n > msg.point_step) {
      *error = "field '" + std::string(name) + "' has datatype " + std::to_string(f.datatype) +
               " at offset " + std::to_string(f.offset) + ", outside a point of " +
               std::to_string(msg.point_step) + " bytes";
      return std::nullopt;
    }
    return Field{f.offset, f.datatype};
  }
  return std::nullopt;
}

bool IsType(const std::optional<Field>& f, PointFieldType t) {
  return f && f->datatype == static_cast<uint8_t>(t);
}

/// The time convention and field: the caller's, or detected from the fields.
bool ChooseTime(const PointCloud2Msg& msg,
                const CloudOptions& options,
                PointTimeConvention* convention,
                std::optional<Field>* field,
                std::string* error) {
  *convention = options.time;
  if (options.time == PointTimeConvention::kNone) return true;
  if (options.time != PointTimeConvention::kAuto) {
    std::string name = options.time_field;
    if (name.empty()) {
      name = options.time == PointTimeConvention::kAbsoluteSeconds   ? "timestamp"
             : options.time == PointTimeConvention::kRelativeSeconds ? "time"
                                                                     : "t";
    }
    *field = Find(msg, name, error);
    if (!*field && error->empty()) *error = "no point field '" + name + "' for the time";
    return field->has_value();
  }
  const std::pair<const char*, PointTimeConvention> candidates[] = {
      {"timestamp", PointTimeConvention::kAbsoluteSeconds},
      {"time", PointTimeConvention::kRelativeSeconds},
      {"t", PointTimeConvention::kRelativeNanoseconds},
      {"offset_time", PointTimeConvention::kRelativeNanoseconds}};
  const PointFieldType expected[] = {PointFieldType::kFloat64, PointFieldType::kFloat32,
                                     PointFieldType::kUint32, PointFieldType::kUint32};
  for (size_t i = 0; i < std::size(candidates); ++i) {
    const std::optional<Field> f = Find(msg, candidates[i].first, error);
    if (!error->empty()) return false;
    if (!IsType(f, expected[i])) continue;
    *field = f;
    *convention = candidates[i].second;
    return true;
  }
  *convention = PointTimeConvention::kNone;
  return true;
}

bool CheckLayout(const PointCloud2Msg& msg, std::string* error) {
  const uint64_t row = static_cast<uint64_t>(msg.point_step) * msg.width;
  if (msg.point_step == 0 && msg.width * uint64_t{msg.height} > 0) {
    *error = "point_step 0";
  } else if (row > msg.row_step) {
    *error =
        "row_step " + std::to_string(msg.row_step) + " < width × point_step " + std::to_string(row);
  } else if (static_cast<uint64_t>(msg.row_step) * msg.height > msg.data.size()) {
    *error = "data holds " + std::to_string(msg.data.size()) + " bytes, height × row_step is " +
             std::to_string(static_cast<uint64_t>(msg.row_step) * msg.height);
  }
  return error->empty();
}

/// Time of one point in ns on the bag's clock; nullopt for a non-finite or absurd value.
/// Offsets are rounded on their own and added to the integer stamp: adding them in double
/// would lose the stamp's last ~8 bits (2⁶⁰ ns).
std::optional<int64_t> PointTime(double v, PointTimeConvention c, int64_t stamp_ns) {
  constexpr double kMaxOffsetNs = 1e18;  // 31 years either way
  if (!std::isfinite(v)) return std::nullopt;
  switch (c) {
    case PointTimeConvention::kAbsoluteSeconds: {
      if (v > kNsThreshold) return v > 9e18 ? std::nullopt : std::optional(std::llround(v));
      if (v < 0.0 || v > 9e9) return std::nullopt;
      // Whole seconds and their fraction apart: both exact in double, so the only error left
      // is the value's own rounding (half a step: 119 ns in 2026), not a second one from ×1e9.
      const double whole = std::floor(v);
      return static_cast<int64_t>(whole) * 1'000'000'000 + std::llround((v - whole) * 1e9);
    }
    case PointTimeConvention::kRelativeSeconds:
      v *= 1e9;
      break;
    case PointTimeConvention::kRelativeNanoseconds:
      break;
    default:
      return stamp_ns;
  }
  if (std::abs(v) > kMaxOffsetNs) return std::nullopt;
  return stamp_ns + std::llround(v);
}

/// Where the fields of one point are, and how its time reads.
struct PointLayout {
  Field x, y, z;
  std::optional<Field> ring, intensity, time;
  PointTimeConvention convention = PointTimeConvention::kNone;
  bool big_endian = false;
  int64_t stamp_ns = 0;
};

bool Locate(const PointCloud2Msg& msg,
            const CloudOptions& options,
            PointLayout* layout,
            PointTimeConvention* convention,
            std::string* error) {
  const std::optional<Field> x = Find(msg, "x", error);
  const std::optional<Field> y = Find(msg, "y", error);
  const std::optional<Field> z = Find(msg, "z", error);
  if (!x || !y || !z) {
    if (error->empty()) *error = "no x, y and z fields";
    return false;
  }
  layout->x = *x;
  layout->y = *y;
  layout->z = *z;
  layout->ring = Find(msg, "ring", error);
  if (!layout->ring) layout->ring = Find(msg, "line", error);
  layout->intensity = Find(msg, "intensity", error);
  if (!error->empty() || !ChooseTime(msg, options, convention, &layout->time, error)) return false;
  layout->convention = *convention;
  layout->big_endian = msg.is_bigendian;
  layout->stamp_ns = msg.header.stamp_ns;
  return true;
}

/// `v` as a float when it is finite and within float's range.
std::optional<float> AsFloat(double v) {
  if (!std::isfinite(v) || std::abs(v) > std::numeric_limits<float>::max()) return std::nullopt;
  return static_cast<float>(v);
}

/// One point; false when a coordinate or its time is not a finite number.
bool ReadPoint(const uint8_t* p, const PointLayout& l, LidarPoint* out, int64_t* t_ns) {
  const auto read = [&](const Field& f) {
    return ReadValue(p + f.offset, f.datatype, l.big_endian);
  };
  const std::optional<float> x = AsFloat(read(l.x));
  const std::optional<float> y = AsFloat(read(l.y));
  const std::optional<float> z = AsFloat(read(l.z));
  const std::optional<int64_t> t =
      l.time ? PointTime(read(*l.time), l.convention, l.stamp_ns) : l.stamp_ns;
  if (!x || !y || !z || !t) return false;
  out->xyz_m = Eigen::Vector3f(*x, *y, *z);
  out->intensity = l.intensity ? AsFloat(read(*l.intensity)).value_or(0.0f) : 0.0f;
  const double ring = l.ring ? read(*l.ring) : 0.0;
  out->ring = ring >= 0.0 && ring <= 65535.0 ? static_cast<uint16_t>(ring) : 0;
  *t_ns = *t;
  return true;
}

}  // namespace

bool ParsePointTimeConvention(const std::string& name, PointTimeConvention* out) {
  for (const auto c : {PointTimeConvention::kAuto, PointTimeConvention::kAbsoluteSeconds,
                       PointTimeConvention::kRelativeSeconds,
                       PointTimeConvention::kRelativeNanoseconds, PointTimeConvention::kNone}) {
    if (name != PointTimeConventionName(c)) continue;
    *out = c;
    return true;
  }
  return false;
}

const char* PointTimeConventionName(PointTimeConvention c) {
  switch (c) {
    case PointTimeConvention::kAuto:
      return "auto";
    case PointTimeConvention::kAbsoluteSeconds:
      return "absolute_s";
    case PointTimeConvention::kRelativeSeconds:
      return "relative_s";
    case PointTimeConvention::kRelativeNanoseconds:
      return "relative_ns";
    case PointTimeConvention::kNone:
      return "none";
  }
  return "?";
}

bool CloudFromPointCloud2(const PointCloud2Msg& msg,
                          const CloudOptions& options,
                          CloudPoints* out,
                          std::string* error) {
  error->clear();
  out->scan.points.clear();
  out->non_finite_points = 0;
  out->points_in = static_cast<uint64_t>(msg.width) * msg.height;
  PointLayout layout;
  if (!CheckLayout(msg, error) || !Locate(msg, options, &layout, &out->time_convention, error)) {
    return false;
  }
  out->has_ring = layout.ring.has_value();
  int64_t t_min = std::numeric_limits<int64_t>::max();
  int64_t t_max = std::numeric_limits<int64_t>::min();
  out->scan.points.reserve(out->points_in);
  for (uint32_t r = 0; r < msg.height; ++r) {
    const uint8_t* row = msg.data.data() + static_cast<size_t>(r) * msg.row_step;
    for (uint32_t c = 0; c < msg.width; ++c) {
      LidarPoint lp;
      int64_t t = 0;
      if (!ReadPoint(row + static_cast<size_t>(c) * msg.point_step, layout, &lp, &t)) {
        ++out->non_finite_points;
        continue;
      }
      lp.dt_ns = t;  // absolute for now, relative below
      t_min = std::min(t_min, t);
      t_max = std::max(t_max, t);
      out->scan.points.push_back(lp);
    }
  }
  for (LidarPoint& p : out->scan.points) p.dt_ns -= t_min;
  out->scan.t_start_ns = out->scan.points.empty() ? msg.header.stamp_ns : t_min;
  out->scan.t_end_ns = out->scan.points.empty() ? msg.header.stamp_ns : t_max;
  out->scan.partial = false;
  return true;
}

}  // namespace swlio::drivers::bag

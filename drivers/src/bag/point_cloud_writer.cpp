// A sweep as rslidar_sdk's XYZIRT PointCloud2 (point_cloud_writer.h).

#include "swlio/drivers/bag/point_cloud_writer.h"

#include <bit>

#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag {
namespace {

using bytes::WriteU16Le;
using bytes::WriteU32Le;
constexpr uint32_t kPointStep = 26;

void PutF32(uint8_t* at, float v) { WriteU32Le(at, std::bit_cast<uint32_t>(v)); }
void PutF64(uint8_t* at, double v) {
  const auto u = std::bit_cast<uint64_t>(v);
  WriteU32Le(at, static_cast<uint32_t>(u));
  WriteU32Le(at + 4, static_cast<uint32_t>(u >> 32));
}

/// Seconds since the epoch as a double, rounded once: 0.24 µs steps in 2026, far below a
/// firing's 2.8 µs (whole seconds and the nanoseconds apart: converting the int64 first would
/// round twice, to 256 ns and then to the double's step).
double Seconds(int64_t t_ns) {
  const int64_t whole = t_ns / 1'000'000'000;
  return static_cast<double>(whole) + static_cast<double>(t_ns - whole * 1'000'000'000) * 1e-9;
}

}  // namespace

void RslidarCloudFromScan(const Scan& scan, const std::string& frame_id, OwnedPointCloud2* out) {
  out->frame_id = frame_id;
  const auto n = static_cast<uint32_t>(scan.points.size());
  out->data.resize(static_cast<size_t>(n) * kPointStep);
  for (uint32_t i = 0; i < n; ++i) {
    const LidarPoint& p = scan.points[i];
    uint8_t* at = out->data.data() + static_cast<size_t>(i) * kPointStep;
    PutF32(at + 0, p.xyz_m.x());
    PutF32(at + 4, p.xyz_m.y());
    PutF32(at + 8, p.xyz_m.z());
    PutF32(at + 12, p.intensity);
    WriteU16Le(at + 16, p.ring);
    PutF64(at + 18, Seconds(scan.t_start_ns + p.dt_ns));
  }
  PointCloud2Msg& m = out->msg;
  m.header.frame_id = out->frame_id;
  m.header.stamp_ns = scan.t_start_ns;
  m.height = 1;
  m.width = n;
  const auto f = [](const char* name, uint32_t offset, PointFieldType type) {
    return PointFieldView{name, offset, static_cast<uint8_t>(type), 1};
  };
  m.fields = {f("x", 0, PointFieldType::kFloat32),    f("y", 4, PointFieldType::kFloat32),
              f("z", 8, PointFieldType::kFloat32),    f("intensity", 12, PointFieldType::kFloat32),
              f("ring", 16, PointFieldType::kUint16), f("timestamp", 18, PointFieldType::kFloat64)};
  m.is_bigendian = false;
  m.point_step = kPointStep;
  m.row_step = kPointStep * n;
  m.data = out->data;
  m.is_dense = true;
}

}  // namespace swlio::drivers::bag

#include "swlio/ipc/point_cloud.h"

#include <bit>
#include <limits>

namespace swlio::ipc {
namespace {

void PutFloatLe(float v, uint8_t* out) {
  const auto bits = std::bit_cast<uint32_t>(v);
  for (int k = 0; k < 4; ++k) out[k] = static_cast<uint8_t>(bits >> (8 * k));
}

float GetFloatLe(const uint8_t* in) {
  uint32_t bits = 0;
  for (int k = 0; k < 4; ++k) bits |= static_cast<uint32_t>(in[k]) << (8 * k);
  return std::bit_cast<float>(bits);
}

bool IsFloatField(const PointField& f, const char* name, uint32_t offset) {
  return f.name == name && f.offset == offset && f.datatype == PointFieldType::kFloat32 &&
         f.count == 1;
}

}  // namespace

std::vector<PointField> XyzFields(bool with_intensity) {
  std::vector<PointField> fields = {{"x", 0, PointFieldType::kFloat32, 1},
                                    {"y", 4, PointFieldType::kFloat32, 1},
                                    {"z", 8, PointFieldType::kFloat32, 1}};
  if (with_intensity) fields.push_back({"intensity", 12, PointFieldType::kFloat32, 1});
  return fields;
}

bool InitXyzCloud(size_t points, bool with_intensity, PointCloud2* cloud) {
  const uint32_t step = with_intensity ? kXyziPointStep : kXyzPointStep;
  if (points > std::numeric_limits<uint32_t>::max() / step) return false;
  cloud->height = 1;
  cloud->width = static_cast<uint32_t>(points);
  cloud->fields = XyzFields(with_intensity);
  cloud->is_bigendian = false;
  cloud->point_step = step;
  cloud->row_step = cloud->width * step;
  cloud->data.assign(cloud->row_step, 0);
  cloud->is_dense = true;
  return true;
}

void SetPoint(size_t i, const std::array<float, 3>& xyz, float intensity, PointCloud2* cloud) {
  uint8_t* p = cloud->data.data() + i * cloud->point_step;
  for (size_t a = 0; a < 3; ++a) PutFloatLe(xyz[a], p + 4 * a);
  if (cloud->point_step >= kXyziPointStep) PutFloatLe(intensity, p + 12);
}

bool HasXyzLayout(const PointCloud2& cloud) {
  bool x = false, y = false, z = false;
  for (const PointField& f : cloud.fields) {
    x = x || IsFloatField(f, "x", 0);
    y = y || IsFloatField(f, "y", 4);
    z = z || IsFloatField(f, "z", 8);
  }
  const uint64_t row_bytes = uint64_t{cloud.width} * cloud.point_step;
  return x && y && z && !cloud.is_bigendian && cloud.point_step >= kXyzPointStep &&
         cloud.row_step >= row_bytes &&
         cloud.data.size() >= uint64_t{cloud.height} * cloud.row_step;
}

std::array<float, 3> XyzAt(const PointCloud2& cloud, size_t i) {
  const size_t row = i / cloud.width;
  const size_t column = i % cloud.width;
  const uint8_t* p = cloud.data.data() + row * cloud.row_step + column * cloud.point_step;
  return {GetFloatLe(p), GetFloatLe(p + 4), GetFloatLe(p + 8)};
}

}  // namespace swlio::ipc

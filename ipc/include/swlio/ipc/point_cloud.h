#pragma once
/// @file
/// The point layout swlio publishes on the map topic, as sensor_msgs/PointCloud2: one row
/// (height 1, width n), little-endian (is_bigendian false), no invalid points (is_dense true):
///
///   offset  field      datatype   count
///   0       x          FLOAT32 7  1      metres in the message's frame_id
///   4       y          FLOAT32 7  1
///   8       z          FLOAT32 7  1
///   12      intensity  FLOAT32 7  1      only with `with_intensity`
///
/// point_step 12 (16 with intensity), row_step = width × point_step. This is what rviz2's
/// PointCloud2 display and pcl_conversions read. Values are written and read byte by byte in
/// little-endian order, never by casting a struct over the buffer.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "swlio/ipc/messages.h"

namespace swlio::ipc {

/// Bytes per point of the layout above.
inline constexpr uint32_t kXyzPointStep = 12;
inline constexpr uint32_t kXyziPointStep = 16;

/// The fields of the layout above: x, y, z (and intensity).
std::vector<PointField> XyzFields(bool with_intensity);

/// Makes `cloud` a height-1 cloud of `points` points with the layout above, every value 0:
/// fields, point_step, row_step, width, data (sized), is_bigendian false, is_dense true.
/// Leaves t_ns and frame_id alone. Returns false (cloud unchanged) when the row would not fit
/// a uint32 row_step.
bool InitXyzCloud(size_t points, bool with_intensity, PointCloud2* cloud);

/// Writes point `i` (i < width) of a cloud made by InitXyzCloud; `intensity` is ignored
/// without the intensity field.
void SetPoint(size_t i, const std::array<float, 3>& xyz, float intensity, PointCloud2* cloud);

/// True when the cloud has x, y, z as single little-endian FLOAT32 fields at offsets 0, 4, 8
/// (any point_step ≥ 12) and its data holds height × row_step ≥ height × width × point_step
/// bytes: what XyzAt reads.
bool HasXyzLayout(const PointCloud2& cloud);

/// Point `i` (row-major over height × width) of a cloud with HasXyzLayout.
std::array<float, 3> XyzAt(const PointCloud2& cloud, size_t i);

}  // namespace swlio::ipc

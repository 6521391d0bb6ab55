#pragma once
/// @file
/// sensor_msgs/PointCloud2 → a swlio Scan: x, y, z (metres, in the message's frame_id, as
/// published), intensity, ring, and every point's own time.
///
/// Per-point time conventions of the common drivers (research/bags.md §6), detected from the
/// field names and types unless the caller says otherwise:
///   - rslidar_sdk (XYZIRT): `timestamp` FLOAT64, absolute seconds since the epoch (rs_driver
///     decoder_RS16.hpp setTimestamp). A value above 10¹⁵ is taken as nanoseconds (the
///     livox_ros_driver2 PointCloud2 writes absolute ns into the same field name and type).
///   - velodyne_pointcloud: `time` FLOAT32, seconds relative to header.stamp (may be negative
///     when the header carries the last packet's time).
///   - ouster-ros: `t` UINT32, nanoseconds relative to header.stamp.
///   - Livox CustomMsg-style clouds: `offset_time` UINT32, nanoseconds relative to header.stamp.
///   - none of these: every point at header.stamp (`kNone`), which the caller should report.
/// Ring: `ring` (UINT8 or UINT16; ouster-ros changed from one to the other) or Livox's `line`.
/// Fields are found by name and read at their declared offset and type with memcpy-free
/// explicit-endian reads (several drivers pack fields unaligned: `timestamp` at byte 18).
/// Points with a non-finite coordinate or time are dropped and counted (LeGO-LOAM #33: RS16
/// NaN points); the Scan's t_start_ns is its earliest point, t_end_ns its latest.

#include <cstdint>
#include <string>

#include "swlio/core/types.h"
#include "swlio/drivers/bag/ros_messages.h"

namespace swlio::drivers::bag {

enum class PointTimeConvention : uint8_t {
  kAuto,                 ///< detect from the fields (above)
  kAbsoluteSeconds,      ///< float64 s since the epoch (or ns when > 10¹⁵)
  kRelativeSeconds,      ///< seconds after header.stamp
  kRelativeNanoseconds,  ///< nanoseconds after header.stamp
  kNone,                 ///< no per-point time: all points at header.stamp
};

/// "auto", "absolute_s", "relative_s", "relative_ns", "none"; false when unknown.
bool ParsePointTimeConvention(const std::string& name, PointTimeConvention* out);
const char* PointTimeConventionName(PointTimeConvention c);

struct CloudOptions {
  PointTimeConvention time = PointTimeConvention::kAuto;
  /// With a convention other than kAuto/kNone: the time field's name; empty = the convention's
  /// usual one (`timestamp`, `time`, `t`).
  std::string time_field;
};

struct CloudPoints {
  Scan scan;  ///< points in frame_id; times on the bag's clock (the publisher's stamps)
  PointTimeConvention time_convention = PointTimeConvention::kNone;  ///< the one used
  bool has_ring = false;
  uint64_t points_in = 0;          ///< width × height
  uint64_t non_finite_points = 0;  ///< dropped: NaN or infinite coordinate or time
};

/// Converts `msg`. False with `error` when the layout is inconsistent (no x/y/z, a field past
/// point_step, data shorter than height × row_step, the requested time field missing).
bool CloudFromPointCloud2(const PointCloud2Msg& msg,
                          const CloudOptions& options,
                          CloudPoints* out,
                          std::string* error);

}  // namespace swlio::drivers::bag

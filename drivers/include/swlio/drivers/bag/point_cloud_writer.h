#pragma once
/// @file
/// A swlio sweep as the sensor_msgs/PointCloud2 rslidar_sdk publishes with its XYZIRT point
/// type (research/bags.md §6; rslidar_sdk doc/howto/05_how_to_change_point_type.md): fields
/// x, y, z, intensity FLOAT32 at bytes 0, 4, 8, 12, ring UINT16 at 16, timestamp FLOAT64
/// (absolute seconds) at 18, 26 bytes per point, packed; one row (height 1), little-endian,
/// dense. header.stamp is the first point's time (rslidar_sdk's shipped config.yaml:
/// `ts_first_point: true`). point_cloud_points.h reads such a cloud back.

#include <cstdint>
#include <string>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/drivers/bag/ros_messages.h"

namespace swlio::drivers::bag {

/// A PointCloud2Msg with the storage its views point into.
struct OwnedPointCloud2 {
  PointCloud2Msg msg;
  std::vector<uint8_t> data;
  std::string frame_id;
};

/// Fills `out` (its storage reused) from `scan` (times: t_start_ns + dt_ns), in `frame_id`.
void RslidarCloudFromScan(const Scan& scan, const std::string& frame_id, OwnedPointCloud2* out);

}  // namespace swlio::drivers::bag

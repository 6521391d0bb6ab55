#pragma once
/// @file
/// `swlio-bag export`: a swlio recording folder (the simulator's or swliod --record's) as a
/// rosbag2 MCAP file, with each sensor as its vendor's ROS 2 driver publishes it, so that a
/// recording opens in Foxglove, plays into a ROS 2 stack, and runs through swlio's bag input:
///   - /rslidar_points  sensor_msgs/PointCloud2, rslidar_sdk's XYZIRT cloud (point_cloud_writer.h)
///                      in frame `rslidar`, one per sweep as the daemon's decoders and scan
///                      assembler make it, stamped on the host clock the recording's clock
///                      models give (as rslidar_sdk with use_lidar_clock: false);
///   - /imu/data        sensor_msgs/Imu in frame `imu_link` (the Xsens ROS 2 driver's topic and
///                      frame): calibrated acceleration with gravity and rate of turn; orientation
///                      not provided (covariance element 0 = −1, sensor_msgs/Imu.msg);
///   - /gnss            sensor_msgs/NavSatFix when the recording has GNSS (manifest gnss: block),
///                      covariance diagonal from the receiver's accuracy estimates;
///   - /odom            nav_msgs/Odometry of `base_link` (twist only) when it has wheel odometry;
///   - /tf_static       tf2_msgs/TFMessage (transient local): imu_link → rslidar (T_imu_lidar)
///                      and, with wheel odometry, imu_link → base_link (T_imu_base).
/// Each message's log time is when the reader delivers it (a sweep at its end), so the file is
/// in receive order. Times are those the recording reader gives (host time; for a daemon
/// recording made with --time-scale, the sensors' time base).
///
/// A bag carries no rig, so beside OUT.mcap goes OUT.swlio.yaml: the effective configuration
/// (`--config`, else the defaults) with the recording's extrinsic, wheel frame and GNSS origin
/// from its manifest, for `swlio-run OUT.mcap --config OUT.swlio.yaml`.

#include <cstdint>
#include <filesystem>
#include <string>

#include "swlio/drivers/bag/decompress.h"

namespace swlio::tools {

struct ExportOptions {
  std::string config;  ///< daemon YAML: LiDAR model and range limits, IMU baud ("" = defaults)
  drivers::bag::Compression compression = drivers::bag::Compression::kZstd;
};

struct ExportCounts {
  uint64_t clouds = 0;
  uint64_t imu = 0;
  uint64_t gnss = 0;
  uint64_t wheel = 0;
};

/// OUT.swlio.yaml for OUT.mcap: the rig's configuration file beside the bag.
std::string RigConfigPath(const std::string& out);

/// Writes `out` (and RigConfigPath(out)) from the recording in `dir`. False with `error` when the
/// recording cannot be read or the file not written.
bool ExportRecording(const std::filesystem::path& dir,
                     const std::string& out,
                     const ExportOptions& options,
                     ExportCounts* counts,
                     std::string* error);

}  // namespace swlio::tools

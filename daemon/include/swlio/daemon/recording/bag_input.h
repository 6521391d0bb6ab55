#pragma once
/// @file
/// A ROS bag (rosbag2 .db3 or folder, MCAP, ROS 1 .bag: drivers/bag/bag_open.h) as swlio-run's
/// and swlio-replay's input, through the daemon's own decoders where the bag holds packets.
///
/// Per message type (topics chosen as drivers/bag/topic_selection.h says):
///   - LiDAR packets (rslidar_sdk, nebula, velodyne_driver): each UDP payload goes through
///     LidarStage (decoder of `lidar.model`, the sensor clock model, the scan assembler), exactly
///     as a packet received live, with the packet's receive time taken as its own stamp, else
///     the message's header.stamp (rslidar_sdk ≤ v1.4 leaves packet stamps zero and stamps the
///     scan message when it publishes it), else the bag's receive time. The LiDAR's header time
///     is the sensor clock, so a bag decodes like a capture whatever the LiDAR's time source.
///   - PointCloud2: one message is one sweep; its points (in the message's frame, which for
///     rslidar_sdk and velodyne_pointcloud is the decoders' frame, REP 103) and per-point times
///     (point_cloud_points.h) are taken as host times. Points outside [min_range_m,
///     max_range_m] are dropped, as the decoders drop them.
///   - sensor_msgs/Imu: acceleration and angular rate in the message's frame at header.stamp.
///   - sensor_msgs/NavSatFix: a fix when status ≥ 0 with a known covariance (√ of the larger
///     horizontal variance as h_acc, of the vertical as v_acc); others are counted as rejected.
///   - nav_msgs/Odometry, geometry_msgs/TwistStamped: forward speed twist.linear.x and yaw rate
///     twist.angular.z of the base frame the message's twist is in.
/// `stamp = kReceive` uses the bag's receive times instead of header stamps everywhere (for
/// bags whose publishers stamp on another clock).
///
/// Bags interleave topics by receive time, which lags each sensor's stamps differently, so
/// events are put in time order (a sweep at its end) through a buffer that holds each event
/// until one `reorder_window_ns` newer has been read.

#include <cstdint>
#include <memory>
#include <string>

#include "swlio/daemon/recording/sensor_input.h"
#include "swlio/drivers/bag/bag_message_stream.h"
#include "swlio/drivers/lidar_config.h"

namespace swlio::daemon {

enum class BagStamp : uint8_t { kHeader, kReceive };

/// What a sensor_msgs/Imu's values are: means over the interval since the previous message (an
/// Xsens MTi's Acceleration and RateOfTurn, and swlio's own bags), or the values at the stamp
/// (turned into means by ImuIntervalMeans, estimator/imu/imu_interval_means.h).
enum class BagImuSamples : uint8_t { kIntervalMean, kInstantaneous };

struct BagInputOptions {
  drivers::bag::TopicChoice topics;  ///< names chosen by the user; empty: found by type
  drivers::bag::CloudOptions cloud;  ///< PointCloud2 per-point time convention
  BagStamp stamp = BagStamp::kHeader;
  BagImuSamples imu_samples = BagImuSamples::kIntervalMean;
  bool gnss = false;   ///< deliver kGnss events (the GNSS topic must exist)
  bool wheel = false;  ///< deliver kWheel events (the wheel topic must exist)
  /// Refuse a bag without an IMU topic. Both estimator modes need the IMU (the LiDAR-only
  /// odometry initializes its attitude from it); false only to read a bag's LiDAR alone.
  bool require_imu = true;
  int64_t reorder_window_ns = 500'000'000;
};

/// Opens the bag at `path` (file or rosbag2 folder). Nullptr with `error` when it is no bag, a
/// topic cannot be chosen, the LiDAR topic's packets are not of `lidar.model`'s family, there is
/// no LiDAR topic or (when required) no IMU topic, or GNSS/wheel events are asked for and their
/// topic is missing.
std::unique_ptr<SensorInput> OpenBagInput(const std::string& path,
                                          const drivers::LidarConfig& lidar,
                                          const BagInputOptions& options,
                                          std::string* error);

/// True when `path` is a recording folder (it holds manifest.yaml, lidar.pcap or imu.xbus),
/// false for anything else (a bag file, a rosbag2 folder, or nothing).
bool IsRecordingFolder(const std::string& path);

}  // namespace swlio::daemon

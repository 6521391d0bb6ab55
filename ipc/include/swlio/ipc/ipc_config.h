#pragma once
/// @file
/// DDS publishing configuration. Topic names are ROS 2 names (without the leading "rt/",
/// which ipc adds), so a ROS 2 node subscribes to "/swlio/pose" directly.

#include <cstdint>
#include <string>

#include "swlio/core/config_issue.h"

namespace swlio::ipc {

struct IpcConfig {
  int64_t domain_id = 0;  ///< DDS domain (ROS_DOMAIN_ID)
  /// Cyclone DDS XML used to create the domain. A relative path is taken from the directory of
  /// the configuration file that names it.
  std::string dds_config_file = "cyclonedds-loopback.xml";
  /// Refuse to start unless the DDS configuration keeps all traffic on loopback.
  bool require_loopback = true;
  std::string pose_topic = "swlio/pose";          ///< IMU-rate pose
  std::string odometry_topic = "swlio/odometry";  ///< scan-rate odometry with covariance
  std::string health_topic = "diagnostics";       ///< 1 Hz health (ROS 2 /diagnostics)
  std::string path_topic = "swlio/path";          ///< keyframe path
  std::string map_topic = "swlio/map";            ///< map cloud (sensor_msgs/PointCloud2)
  /// The keyframe path holds the newest this many keyframes: bounded memory and message size
  /// on a robot that patrols for days (a soak saw the whole path grow with every lap).
  int64_t path_max_poses = 5000;
  /// The published map cloud holds at most this many points (12 bytes each): the voxel is
  /// coarsened until it fits (daemon/output/map_publisher.h), bounding the sample's size.
  int64_t map_max_points = 250'000;
  /// Mapping: the map cloud is rebuilt and published as the map grows and after loop
  /// corrections, at most once per this period (s). Localizing: the saved map is published
  /// once at start. 0: never.
  double map_publish_period_s = 10.0;
  /// The clock of every published header stamp: "realtime" (CLOCK_REALTIME, what ROS 2 nodes
  /// stamp and look up in; the daemon's monotonic times plus the tracked offset, stepping when
  /// the wall clock is stepped) or "monotonic" (CLOCK_MONOTONIC, the daemon's own time base;
  /// meaningful only on this host). daemon/output/stamp_clock.h.
  std::string stamp_clock = "realtime";

  ConfigIssues Validate() const;
};

}  // namespace swlio::ipc

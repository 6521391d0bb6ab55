#pragma once
/// @file
/// DDS publishing configuration. Topic names are ROS 2 names (without the leading "rt/",
/// which ipc adds), so a ROS 2 node subscribes to "/swlio/pose" directly.

#include <cstdint>
#include <string>

#include "swlio/core/config_issue.h"

namespace swlio::ipc {

/// The frame ids of the published messages (REP 105, "Coordinate Frames for Mobile
/// Platforms"): `map` (the loop-closed, world-fixed frame), `odom` (continuous, drifting),
/// `base_link` (the robot base, rigidly attached), and the sensors' frames. tf2 frame ids: no
/// leading '/', all distinct.
struct FrameNames {
  std::string map = "map";
  std::string odom = "odom";
  std::string base_link = "base_link";
  std::string imu = "imu_link";
  std::string lidar = "lidar_link";

  ConfigIssues Validate() const;
};

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
  /// Scan-rate odometry of base_link in the odom frame: the estimator's own, continuous pose
  /// without loop-closure corrections (REP 105 odom), beside the map-frame odometry_topic.
  std::string odom_odometry_topic = "swlio/odometry/odom";
  std::string tf_topic = "tf";                ///< tf2's /tf: odom → base_link, map → odom
  std::string tf_static_topic = "tf_static";  ///< tf2's /tf_static: base_link → imu, lidar
  /// The current sweep for viewers (rviz2, Foxglove): de-skewed and registered, in the map
  /// frame at the sweep's end, BEST_EFFORT (a viewer selects Best Effort, as for any sensor
  /// stream). Empty: not published.
  std::string sweep_topic = "swlio/cloud_registered";
  /// Input: operators' pose hints (rviz2's "2D Pose Estimate" publishes /initialpose,
  /// geometry_msgs/PoseWithCovarianceStamped of base_link in the map frame): relocalize in a
  /// saved map (map.localize) or re-anchor the map being built. Empty (the default): not read.
  std::string initialpose_topic;
  FrameNames frames;
  /// map → odom is published whenever the correction changes and otherwise at least once per
  /// this period (s; 0: with every pose). tf2 resolves map → base_link only up to the newest
  /// map → odom stamp, so this bounds how old a "latest" map-frame lookup can be.
  double map_odom_period_s = 0.1;
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

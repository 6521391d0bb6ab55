#pragma once
/// @file
/// The QoS of each swlio topic, chosen like ROS 2 so that a ROS 2 node's default subscription
/// (RELIABLE, VOLATILE, KEEP_LAST 10) matches every topic without a QoS override.
///
/// - pose (IMU rate): RELIABLE, VOLATILE, KEEP_LAST 10. Matches reliable and best-effort
///   readers; keep-last never blocks the writer.
/// - odometry (scan rate): RELIABLE, VOLATILE, KEEP_LAST 10, as ROS 2's default.
/// - health (/diagnostics): RELIABLE, VOLATILE, KEEP_LAST 10, as ROS 2's diagnostic_updater.
/// - path (keyframes): RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 1. Latched: late joiners get the
///   last path (like /map).
/// - map (PointCloud2, MBs): RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 1. Latched: rviz2 started
///   later gets the newest map; the writer keeps one map, never a backlog.
/// - odom_odometry: as odometry.
/// - tf: RELIABLE, VOLATILE, KEEP_LAST 100, tf2_ros's DynamicBroadcasterQoS (tf2_ros/qos.hpp:
///   rclcpp::QoS(100)).
/// - tf_static: RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 1, tf2_ros's StaticBroadcasterQoS
///   (rclcpp::QoS(1).transient_local()): one sample holding every static transform, latched.
/// - sweep (PointCloud2, ~270 kB at scan rate): BEST_EFFORT, VOLATILE, KEEP_LAST 1, as a sensor
///   stream (rclcpp::SensorDataQoS is best effort): a viewer that falls behind misses sweeps,
///   the writer never resends a stale one. A ROS 2 reader must ask for best effort.
///
/// Every writer also pins data representation XCDR1 (Fast DDS 2.9 reads only XCDR1). Deadline,
/// lifespan, liveliness (AUTOMATIC) and ownership (SHARED) stay at the DDS defaults, as in ROS 2.
/// A best-effort writer would not match ROS 2's default reliable reader, hence RELIABLE even at
/// IMU rate; with KEEP_LAST a slow reader loses old samples instead of blocking the publisher.

#include "swlio/ipc/messages.h"

namespace swlio::ipc {

enum class Reliability : uint8_t { kBestEffort, kReliable };
enum class Durability : uint8_t { kVolatile, kTransientLocal };

struct QosProfile {
  Reliability reliability = Reliability::kReliable;
  Durability durability = Durability::kVolatile;
  int depth = 10;  ///< KEEP_LAST depth
};

/// The writer QoS of `topic` (table above).
constexpr QosProfile WriterQos(Topic topic) {
  if (topic == Topic::kPath || topic == Topic::kMap || topic == Topic::kTfStatic) {
    return {Reliability::kReliable, Durability::kTransientLocal, 1};
  }
  if (topic == Topic::kTf) return {Reliability::kReliable, Durability::kVolatile, 100};
  if (topic == Topic::kSweep) return {Reliability::kBestEffort, Durability::kVolatile, 1};
  return {Reliability::kReliable, Durability::kVolatile, 10};
}

}  // namespace swlio::ipc

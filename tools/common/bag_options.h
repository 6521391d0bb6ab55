#pragma once
/// @file
/// The command-line options swlio-run and swlio-replay share for reading a ROS bag
/// (daemon/recording/bag_input.h). Header-only: tools/common is no program of its own.

#include <CLI/CLI.hpp>
#include <string>

#include "swlio/daemon/recording/bag_input.h"
#include "swlio/drivers/bag/point_cloud_points.h"

namespace swlio::tools {

struct BagCliOptions {
  std::string lidar_topic, imu_topic, gnss_topic, wheel_topic;
  std::string point_time = "auto", point_time_field, stamp = "header";
  std::string imu_samples = "interval-mean";
};

inline void AddBagOptions(CLI::App& app, BagCliOptions* o) {
  app.add_option("--lidar-topic", o->lidar_topic,
                 "bag input: the LiDAR topic (packets or sensor_msgs/PointCloud2); default: the "
                 "only one of such a type");
  app.add_option("--imu-topic", o->imu_topic, "bag input: the sensor_msgs/Imu topic");
  app.add_option("--gnss-topic", o->gnss_topic,
                 "bag input: the sensor_msgs/NavSatFix topic (with --gnss on)");
  app.add_option("--wheel-topic", o->wheel_topic,
                 "bag input: the nav_msgs/Odometry or geometry_msgs/TwistStamped topic of the "
                 "base frame (with --wheel on)");
  app.add_option("--point-time", o->point_time,
                 "bag input, PointCloud2: per-point time convention (auto: from the field names)")
      ->check(CLI::IsMember({"auto", "absolute_s", "relative_s", "relative_ns", "none"}))
      ->capture_default_str();
  app.add_option("--point-time-field", o->point_time_field,
                 "bag input, PointCloud2: the per-point time field's name, with --point-time "
                 "other than auto/none");
  app.add_option("--bag-stamp", o->stamp,
                 "bag input: times from the messages' header stamps, or the bag's receive "
                 "times (publishers stamping on another clock)")
      ->check(CLI::IsMember({"header", "receive"}))
      ->capture_default_str();
  app.add_option("--imu-samples", o->imu_samples,
                 "bag input: sensor_msgs/Imu values are means over the interval since the "
                 "previous message (an Xsens MTi's, swlio's bags) or the values at the stamp")
      ->check(CLI::IsMember({"interval-mean", "instantaneous"}))
      ->capture_default_str();
}

inline daemon::BagInputOptions ToBagInputOptions(const BagCliOptions& o) {
  daemon::BagInputOptions b;
  b.topics = {o.lidar_topic, o.imu_topic, o.gnss_topic, o.wheel_topic};
  drivers::bag::ParsePointTimeConvention(o.point_time, &b.cloud.time);  // checked by CLI11
  b.cloud.time_field = o.point_time_field;
  b.stamp = o.stamp == "receive" ? daemon::BagStamp::kReceive : daemon::BagStamp::kHeader;
  b.imu_samples = o.imu_samples == "instantaneous" ? daemon::BagImuSamples::kInstantaneous
                                                   : daemon::BagImuSamples::kIntervalMean;
  return b;
}

}  // namespace swlio::tools

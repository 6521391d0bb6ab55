#pragma once
/// @file
/// MCAP `ros2msg` schema texts of the messages swlio writes (research/bags.md §3.6; MCAP
/// registry, "ros2msg"): the type's own fields, then each type it uses, depth-first with each
/// one's dependencies in sorted order and every type once, each after a line of 80 '=' and a
/// line "MSG: pkg/Type" — the order rosbag2's LocalMessageDefinitionSource writes. Fields and
/// constants are those of the ROS 2 Jazzy definitions (ros2/common_interfaces,
/// ros2/rcl_interfaces, ros2/geometry2's tf2_msgs), without their comments.

#include <string>
#include <string_view>

namespace swlio::drivers::bag {

/// The schema of `type` ("sensor_msgs/msg/Imu" or "sensor_msgs/Imu"); empty when swlio does
/// not know the type.
std::string Ros2MsgSchema(std::string_view type);

}  // namespace swlio::drivers::bag

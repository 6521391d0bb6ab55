#pragma once
/// @file
/// One text line per sample received by Fast DDS, exact enough to compare bit for bit: every
/// double as its IEEE-754 bit pattern (16 hex digits), every string as "x" + its bytes in hex
/// (so empty strings, spaces and UTF-8 survive whitespace splitting), stamps as "sec nanosec".
///
///   pose <stamp> <frame> <pose> <cov×36>
///   odometry <stamp> <frame> <child_frame> <pose> <cov×36> <twist> <cov×36>
///   health <stamp> <frame> <n> { <level> <name> <message> <hardware_id> <m> { <key> <value> }×m
///   }×n path <stamp> <frame> <n> { <stamp> <frame> <pose> }×n
///   map <stamp> <frame> <height> <width> <n> { <name> <offset> <datatype> <count> }×n
///       <is_bigendian> <point_step> <row_step> <is_dense> <data bytes> <data FNV-1a 64, hex>
///
/// where <pose> is x y z qx qy qz qw and <twist> is vx vy vz wx wy wz. A map cloud's data
/// (up to megabytes) is summarized by its size and digest (swlio/core/fnv1a.h).

#include <string>

#include "diagnostic_msgs.h"
#include "geometry_msgs.h"
#include "nav_msgs.h"
#include "sensor_msgs.h"

namespace swlio::tools::fastdds_echo {

std::string Line(const geometry_msgs::msg::dds_::PoseWithCovarianceStamped_& m);
std::string Line(const nav_msgs::msg::dds_::Odometry_& m);
std::string Line(const diagnostic_msgs::msg::dds_::DiagnosticArray_& m);
std::string Line(const nav_msgs::msg::dds_::Path_& m);
std::string Line(const sensor_msgs::msg::dds_::PointCloud2_& m);

}  // namespace swlio::tools::fastdds_echo

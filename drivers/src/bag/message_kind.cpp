// Which ROS message type a bag topic carries (message_decoder.h, ClassifyTopic).

#include <string>
#include <string_view>

#include "swlio/drivers/bag/message_decoder.h"

namespace swlio::drivers::bag {
namespace {

// ROS 1 md5sums of the two RslidarPacket generations (research/bags.md §4, computed from the
// .msg texts with the genmsg algorithm; they match rslidar_sdk@78d2abb src/msg/ros_msg/
// rslidar_packet_legacy.hpp and rslidar_packet.hpp).
constexpr std::string_view kRslidarPacketLegacyMd5 = "1e4288e00b9222ea477b73350bf24f51";
constexpr std::string_view kRslidarPacketMd5 = "4b1cc155a9097c0cb935a7abf46d6eef";

RosMessageKind RslidarPacketGeneration(const BagTopic& topic) {
  if (topic.md5sum == kRslidarPacketLegacyMd5) return RosMessageKind::kRslidarPacketLegacy;
  if (topic.md5sum == kRslidarPacketMd5) return RosMessageKind::kRslidarPacket;
  // The definitions' texts: v1.5 declares is_difop, the legacy one a fixed uint8[1248].
  if (topic.definition.find("is_difop") != std::string::npos) return RosMessageKind::kRslidarPacket;
  if (topic.definition.find("uint8[1248]") != std::string::npos) {
    return RosMessageKind::kRslidarPacketLegacy;
  }
  return RosMessageKind::kRslidarPacketEither;
}

}  // namespace

std::string NormalizeTypeName(std::string_view type) {
  std::string t(type);
  const size_t at = t.find("/msg/");
  if (at != std::string::npos) t.erase(at, 4);
  return t;
}

RosMessageKind ClassifyTopic(const BagTopic& topic) {
  const std::string t = NormalizeTypeName(topic.type);
  if (t == "rslidar_msg/RslidarScan" || t == "rslidar_msgs/rslidarScan") {
    return RosMessageKind::kRslidarScan;
  }
  if (t == "rslidar_msgs/rslidarPacket") return RosMessageKind::kRslidarPacketLegacy;
  if (t == "rslidar_msg/RslidarPacket") return RslidarPacketGeneration(topic);
  if (t == "robosense_msgs/RobosenseScan") return RosMessageKind::kRobosenseScan;
  if (t == "velodyne_msgs/VelodyneScan") return RosMessageKind::kVelodyneScan;
  if (t == "sensor_msgs/PointCloud2") return RosMessageKind::kPointCloud2;
  if (t == "sensor_msgs/Imu") return RosMessageKind::kImu;
  if (t == "sensor_msgs/NavSatFix") return RosMessageKind::kNavSatFix;
  if (t == "nav_msgs/Odometry") return RosMessageKind::kOdometry;
  if (t == "geometry_msgs/TwistStamped") return RosMessageKind::kTwistStamped;
  return RosMessageKind::kUnknown;
}

const char* KindName(RosMessageKind kind) {
  switch (kind) {
    case RosMessageKind::kUnknown:
      return "unknown";
    case RosMessageKind::kRslidarScan:
      return "RslidarScan";
    case RosMessageKind::kRslidarPacketLegacy:
      return "RslidarPacket (legacy)";
    case RosMessageKind::kRslidarPacket:
      return "RslidarPacket";
    case RosMessageKind::kRslidarPacketEither:
      return "RslidarPacket (either generation)";
    case RosMessageKind::kRobosenseScan:
      return "RobosenseScan";
    case RosMessageKind::kVelodyneScan:
      return "VelodyneScan";
    case RosMessageKind::kPointCloud2:
      return "PointCloud2";
    case RosMessageKind::kImu:
      return "Imu";
    case RosMessageKind::kNavSatFix:
      return "NavSatFix";
    case RosMessageKind::kOdometry:
      return "Odometry";
    case RosMessageKind::kTwistStamped:
      return "TwistStamped";
  }
  return "unknown";
}

}  // namespace swlio::drivers::bag

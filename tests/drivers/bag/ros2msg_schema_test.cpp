// ros2msg schema texts: the root type's fields first, then each dependency once, depth-first
// in sorted order, behind rosbag2's delimiter (research/bags.md §3.6).

#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "swlio/drivers/bag/ros2msg_schema.h"

namespace swlio::drivers::bag {
namespace {

std::vector<std::string> Dependencies(const std::string& schema) {
  std::vector<std::string> out;
  const std::regex msg("\n={80}\nMSG: ([^\n]+)\n");
  for (auto it = std::sregex_iterator(schema.begin(), schema.end(), msg);
       it != std::sregex_iterator(); ++it) {
    out.push_back((*it)[1]);
  }
  return out;
}

TEST(Ros2MsgSchema, PointCloud2AsRosbag2WritesIt) {
  const std::string s = Ros2MsgSchema("sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(s.rfind("std_msgs/Header header\nuint32 height\n", 0), 0u) << s;
  // rosbag2's generator visits PointCloud2's dependencies sorted: sensor_msgs/PointField
  // before std_msgs/Header, whose own dependency follows it.
  EXPECT_EQ(Dependencies(s), (std::vector<std::string>{"sensor_msgs/PointField", "std_msgs/Header",
                                                       "builtin_interfaces/Time"}));
}

TEST(Ros2MsgSchema, EveryTypeOnceAndBareNamesInTheirPackage) {
  const std::vector<std::string> odom = Dependencies(Ros2MsgSchema("nav_msgs/Odometry"));
  EXPECT_EQ(odom, (std::vector<std::string>{
                      "geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose",
                      "geometry_msgs/Point", "geometry_msgs/Quaternion",
                      "geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist",
                      "geometry_msgs/Vector3", "std_msgs/Header", "builtin_interfaces/Time"}));
  EXPECT_EQ(Dependencies(Ros2MsgSchema("tf2_msgs/msg/TFMessage")),
            (std::vector<std::string>{"geometry_msgs/TransformStamped", "geometry_msgs/Transform",
                                      "geometry_msgs/Quaternion", "geometry_msgs/Vector3",
                                      "std_msgs/Header", "builtin_interfaces/Time"}));
  EXPECT_EQ(Dependencies(Ros2MsgSchema("sensor_msgs/msg/Imu")).size(), 4u);
  EXPECT_EQ(Dependencies(Ros2MsgSchema("sensor_msgs/msg/NavSatFix")).size(), 3u);
}

TEST(Ros2MsgSchema, UnknownTypeIsEmpty) {
  EXPECT_TRUE(Ros2MsgSchema("rslidar_msg/msg/RslidarPacket").empty());
  EXPECT_TRUE(Ros2MsgSchema("").empty());
}

}  // namespace
}  // namespace swlio::drivers::bag

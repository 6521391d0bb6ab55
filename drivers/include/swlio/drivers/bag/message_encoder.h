#pragma once
/// @file
/// The structs of ros_messages.h serialized back (XCDR1 little-endian or ROS 1), field for
/// field as message_decoder.h reads them: for MCAP export and for tests. CDR output is padded
/// to a multiple of 4 bytes, as the ROS 2 RMWs write it.

#include <cstdint>
#include <span>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/ros_messages.h"

namespace swlio::drivers::bag {

/// `kind` is one of the packet kinds (not kRslidarPacketEither). Packets must have the size
/// the kind fixes (1248 RoboSense, 1206 Velodyne, ≤ 1500 RobosenseScan); false otherwise.
bool EncodeLidarPackets(RosMessageKind kind,
                        const LidarPacketsMsg& msg,
                        MessageEncoding encoding,
                        std::vector<uint8_t>* out);
std::vector<uint8_t> EncodePointCloud2(const PointCloud2Msg& msg, MessageEncoding encoding);
std::vector<uint8_t> EncodeImu(const ImuMsg& msg, MessageEncoding encoding);
std::vector<uint8_t> EncodeNavSatFix(const NavSatFixMsg& msg, MessageEncoding encoding);
std::vector<uint8_t> EncodeOdometry(const OdometryMsg& msg, MessageEncoding encoding);
std::vector<uint8_t> EncodeTwistStamped(const TwistStampedMsg& msg, MessageEncoding encoding);
/// tf2_msgs/TFMessage: geometry_msgs/TransformStamped[] transforms.
std::vector<uint8_t> EncodeTfMessage(std::span<const TransformStampedMsg> transforms,
                                     MessageEncoding encoding);

}  // namespace swlio::drivers::bag

#pragma once
/// @file
/// Serialized ROS messages (CDR or ROS 1) → the plain structs of ros_messages.h.
///
/// A topic's kind comes from its type name, and for the two incompatible generations of
/// rslidar_msg/RslidarPacket from its stored definition (rosbag2 db schema 4, MCAP schema, ROS 1
/// message_definition) or ROS 1 md5sum (research/bags.md §2.2, §4: legacy 1e4288e0…, v1.5
/// 4b1cc155…). Each decode checks the whole layout: a message whose bytes do not match its
/// declared type fails with the byte offset and field (`MessageReader::Failure`).
///
/// Decoding allocates only when a packet or field list outgrows what an earlier message of the
/// same struct needed: reuse one `DecodedMessage` for a whole bag.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/ros_messages.h"

namespace swlio::drivers::bag {

/// The kind of a topic's messages; kUnknown for types swlio does not read.
RosMessageKind ClassifyTopic(const BagTopic& topic);

/// "sensor_msgs/msg/Imu" → "sensor_msgs/Imu" (ROS 2 names carry "/msg/", ROS 1 names do not).
std::string NormalizeTypeName(std::string_view type);

/// One decoded message; only the member `kind` names is meaningful.
struct DecodedMessage {
  RosMessageKind kind = RosMessageKind::kUnknown;
  LidarPacketsMsg packets;  ///< the RoboSense and Velodyne kinds
  PointCloud2Msg cloud;
  ImuMsg imu;
  NavSatFixMsg fix;
  OdometryMsg odometry;
  TwistStampedMsg twist;
};

/// Decodes `bytes` (one message of `encoding`) as `kind` into `out`. On failure returns false
/// and sets `error` to where and why ("byte 1290: packets[].data needs 1248 bytes, 37 left").
bool DecodeMessage(RosMessageKind kind,
                   MessageEncoding encoding,
                   std::span<const uint8_t> bytes,
                   DecodedMessage* out,
                   std::string* error);

/// header.stamp of a decoded message; nullopt for the header-less legacy packet type.
std::optional<int64_t> HeaderStamp(const DecodedMessage& message);

/// The decoders behind DecodeMessage, one per family, on a reader already past Begin().
bool DecodeLidarPackets(RosMessageKind kind, MessageReader& r, LidarPacketsMsg* out);
bool DecodePointCloud2(MessageReader& r, PointCloud2Msg* out);
bool DecodeImu(MessageReader& r, ImuMsg* out);
bool DecodeNavSatFix(MessageReader& r, NavSatFixMsg* out);
bool DecodeOdometry(MessageReader& r, OdometryMsg* out);
bool DecodeTwistStamped(MessageReader& r, TwistStampedMsg* out);

}  // namespace swlio::drivers::bag

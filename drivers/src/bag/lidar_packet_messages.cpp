// Packet-carrying LiDAR messages → raw UDP payloads (message_decoder.h). Layouts, as the .msg
// files define them (research/bags.md §2.2–2.4):
//   rslidar_msg ≤ v1.4 (894853c msg/): RslidarPacket {builtin_interfaces/Time stamp;
//     uint8[1248] data}; RslidarScan {std_msgs/Header header; RslidarPacket[] packets}.
//   rslidar_msg ≥ v1.5 (fe8a95c msg/RslidarPacket.msg): {std_msgs/Header header;
//     uint8 is_difop; uint8 is_frame_begin; uint8[] data}.
//   velodyne_msgs (ros-drivers/velodyne 04a7ca7): VelodynePacket {Time stamp;
//     uint8[1206] data}; VelodyneScan {Header header; VelodynePacket[] packets}.
//   robosense_msgs (tier4/nebula): RobosensePacket {Time stamp; uint8 is_difop;
//     uint8[1500] data; uint32 size}; RobosenseScan {Header header; RobosensePacket[] packets}.
// In CDR each array element starts 4-aligned (Time), so the strides are 1256, 1216 and 1516.

#include "swlio/drivers/bag/message_decoder.h"

namespace swlio::drivers::bag {
namespace {

constexpr size_t kRoboSensePacketBytes = 1248;
constexpr size_t kVelodynePacketBytes = 1206;
constexpr size_t kRobosenseDataBytes = 1500;
constexpr size_t kTimeBytes = 8;

/// packets[] of {Time stamp; uint8[payload_bytes] data}.
void ReadFixedPackets(MessageReader& r, size_t payload_bytes, LidarPacketsMsg* out) {
  const uint32_t n = r.SequenceLength("packets", kTimeBytes + payload_bytes);
  for (uint32_t i = 0; i < n && r.ok(); ++i) {
    LidarPacketView p;
    p.stamp_ns = r.Time("packets[].stamp");
    p.payload = r.Bytes(payload_bytes, "packets[].data");
    out->packets.push_back(p);
  }
}

/// packets[] of robosense_msgs/RobosensePacket; `size` selects the valid prefix of data.
void ReadRobosensePackets(MessageReader& r, LidarPacketsMsg* out) {
  const uint32_t n = r.SequenceLength("packets", kTimeBytes + 1 + kRobosenseDataBytes + 4);
  for (uint32_t i = 0; i < n && r.ok(); ++i) {
    LidarPacketView p;
    p.stamp_ns = r.Time("packets[].stamp");
    p.role = r.U8("packets[].is_difop") != 0 ? PacketRole::kInfo : PacketRole::kData;
    const std::span<const uint8_t> data = r.Bytes(kRobosenseDataBytes, "packets[].data");
    const uint32_t size = r.U32("packets[].size");
    if (size > data.size()) {
      r.Invalid("packets[].size (over 1500)");
      return;
    }
    p.payload = data.first(size);
    out->packets.push_back(p);
  }
}

/// rslidar_msg ≥ v1.5 RslidarPacket: one packet with a header and a role.
void ReadRslidarPacket(MessageReader& r, LidarPacketsMsg* out) {
  out->has_header = true;
  out->header = r.Header();
  LidarPacketView p;
  p.stamp_ns = out->header.stamp_ns;
  p.role = r.U8("is_difop") != 0 ? PacketRole::kInfo : PacketRole::kData;
  r.U8("is_frame_begin");
  const uint32_t n = r.SequenceLength("data", 1);
  p.payload = r.Bytes(n, "data");
  out->packets.push_back(p);
}

}  // namespace

bool DecodeLidarPackets(RosMessageKind kind, MessageReader& r, LidarPacketsMsg* out) {
  out->packets.clear();
  out->has_header = false;
  out->header = {};
  switch (kind) {
    case RosMessageKind::kRslidarScan:
      out->has_header = true;
      out->header = r.Header();
      ReadFixedPackets(r, kRoboSensePacketBytes, out);
      break;
    case RosMessageKind::kRslidarPacketLegacy: {
      LidarPacketView p;
      p.stamp_ns = r.Time("stamp");
      p.payload = r.Bytes(kRoboSensePacketBytes, "data");
      out->packets.push_back(p);
      break;
    }
    case RosMessageKind::kRslidarPacket:
      ReadRslidarPacket(r, out);
      break;
    case RosMessageKind::kRobosenseScan:
      out->has_header = true;
      out->header = r.Header();
      ReadRobosensePackets(r, out);
      break;
    case RosMessageKind::kVelodyneScan:
      out->has_header = true;
      out->header = r.Header();
      ReadFixedPackets(r, kVelodynePacketBytes, out);
      break;
    default:
      return false;
  }
  return r.Finish();
}

}  // namespace swlio::drivers::bag

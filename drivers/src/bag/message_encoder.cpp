// ros_messages.h structs → serialized messages; the field orders are the decoders'
// (lidar_packet_messages.cpp, sensor_messages.cpp, point_cloud2_message.cpp).

#include "swlio/drivers/bag/message_encoder.h"

#include "swlio/drivers/bag/message_writer.h"

namespace swlio::drivers::bag {
namespace {

void Vector3(MessageWriter& w, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) w.F64(v[i]);
}

void Quaternion(MessageWriter& w, const Eigen::Quaterniond& q) {
  w.F64(q.x());
  w.F64(q.y());
  w.F64(q.z());
  w.F64(q.w());
}

template <size_t N>
void F64Array(MessageWriter& w, const std::array<double, N>& a) {
  for (const double v : a) w.F64(v);
}

bool FixedPackets(MessageWriter& w, const LidarPacketsMsg& msg, size_t payload_bytes) {
  w.U32(static_cast<uint32_t>(msg.packets.size()));
  for (const LidarPacketView& p : msg.packets) {
    if (p.payload.size() != payload_bytes) return false;
    w.Time(p.stamp_ns);
    w.Bytes(p.payload);
  }
  return true;
}

bool RobosensePackets(MessageWriter& w, const LidarPacketsMsg& msg) {
  static constexpr std::array<uint8_t, 1500> kZeros{};
  w.U32(static_cast<uint32_t>(msg.packets.size()));
  for (const LidarPacketView& p : msg.packets) {
    if (p.payload.size() > kZeros.size()) return false;
    w.Time(p.stamp_ns);
    w.U8(p.role == PacketRole::kInfo ? 1 : 0);
    w.Bytes(p.payload);
    w.Bytes(std::span(kZeros).first(kZeros.size() - p.payload.size()));
    w.U32(static_cast<uint32_t>(p.payload.size()));
  }
  return true;
}

bool Packets(RosMessageKind kind, MessageWriter& w, const LidarPacketsMsg& msg) {
  switch (kind) {
    case RosMessageKind::kRslidarScan:
      w.Header(msg.header.stamp_ns, msg.header.frame_id);
      return FixedPackets(w, msg, 1248);
    case RosMessageKind::kVelodyneScan:
      w.Header(msg.header.stamp_ns, msg.header.frame_id);
      return FixedPackets(w, msg, 1206);
    case RosMessageKind::kRobosenseScan:
      w.Header(msg.header.stamp_ns, msg.header.frame_id);
      return RobosensePackets(w, msg);
    case RosMessageKind::kRslidarPacketLegacy:
      if (msg.packets.size() != 1 || msg.packets[0].payload.size() != 1248) return false;
      w.Time(msg.packets[0].stamp_ns);
      w.Bytes(msg.packets[0].payload);
      return true;
    case RosMessageKind::kRslidarPacket:
      if (msg.packets.size() != 1) return false;
      w.Header(msg.header.stamp_ns, msg.header.frame_id);
      w.U8(msg.packets[0].role == PacketRole::kInfo ? 1 : 0);
      w.U8(0);  // is_frame_begin: not kept by the decoder
      w.U32(static_cast<uint32_t>(msg.packets[0].payload.size()));
      w.Bytes(msg.packets[0].payload);
      return true;
    default:
      return false;
  }
}

}  // namespace

bool EncodeLidarPackets(RosMessageKind kind,
                        const LidarPacketsMsg& msg,
                        MessageEncoding encoding,
                        std::vector<uint8_t>* out) {
  MessageWriter w(encoding);
  if (!Packets(kind, w, msg)) return false;
  w.PadToFour();
  *out = w.Take();
  return true;
}

std::vector<uint8_t> EncodePointCloud2(const PointCloud2Msg& msg, MessageEncoding encoding) {
  MessageWriter w(encoding);
  w.Header(msg.header.stamp_ns, msg.header.frame_id);
  w.U32(msg.height);
  w.U32(msg.width);
  w.U32(static_cast<uint32_t>(msg.fields.size()));
  for (const PointFieldView& f : msg.fields) {
    w.String(f.name);
    w.U32(f.offset);
    w.U8(f.datatype);
    w.U32(f.count);
  }
  w.U8(msg.is_bigendian ? 1 : 0);
  w.U32(msg.point_step);
  w.U32(msg.row_step);
  w.U32(static_cast<uint32_t>(msg.data.size()));
  w.Bytes(msg.data);
  w.U8(msg.is_dense ? 1 : 0);
  w.PadToFour();
  return w.Take();
}

std::vector<uint8_t> EncodeImu(const ImuMsg& msg, MessageEncoding encoding) {
  MessageWriter w(encoding);
  w.Header(msg.header.stamp_ns, msg.header.frame_id);
  Quaternion(w, msg.orientation);
  F64Array(w, msg.orientation_covariance);
  Vector3(w, msg.angular_velocity_radps);
  F64Array(w, msg.angular_velocity_covariance);
  Vector3(w, msg.linear_acceleration_mps2);
  F64Array(w, msg.linear_acceleration_covariance);
  w.PadToFour();
  return w.Take();
}

std::vector<uint8_t> EncodeNavSatFix(const NavSatFixMsg& msg, MessageEncoding encoding) {
  MessageWriter w(encoding);
  w.Header(msg.header.stamp_ns, msg.header.frame_id);
  w.U8(static_cast<uint8_t>(msg.status));
  w.U16(msg.service);
  w.F64(msg.latitude_deg);
  w.F64(msg.longitude_deg);
  w.F64(msg.altitude_m);
  F64Array(w, msg.position_covariance_m2);
  w.U8(msg.position_covariance_type);
  w.PadToFour();
  return w.Take();
}

std::vector<uint8_t> EncodeOdometry(const OdometryMsg& msg, MessageEncoding encoding) {
  MessageWriter w(encoding);
  w.Header(msg.header.stamp_ns, msg.header.frame_id);
  w.String(msg.child_frame_id);
  Vector3(w, msg.position_m);
  Quaternion(w, msg.orientation);
  F64Array(w, msg.pose_covariance);
  Vector3(w, msg.linear_velocity_mps);
  Vector3(w, msg.angular_velocity_radps);
  F64Array(w, msg.twist_covariance);
  w.PadToFour();
  return w.Take();
}

std::vector<uint8_t> EncodeTwistStamped(const TwistStampedMsg& msg, MessageEncoding encoding) {
  MessageWriter w(encoding);
  w.Header(msg.header.stamp_ns, msg.header.frame_id);
  Vector3(w, msg.linear_velocity_mps);
  Vector3(w, msg.angular_velocity_radps);
  w.PadToFour();
  return w.Take();
}

std::vector<uint8_t> EncodeTfMessage(std::span<const TransformStampedMsg> transforms,
                                     MessageEncoding encoding) {
  MessageWriter w(encoding);
  w.U32(static_cast<uint32_t>(transforms.size()));
  for (const TransformStampedMsg& t : transforms) {
    w.Header(t.header.stamp_ns, t.header.frame_id);
    w.String(t.child_frame_id);
    Vector3(w, t.translation_m);
    Quaternion(w, t.rotation);
  }
  w.PadToFour();
  return w.Take();
}

}  // namespace swlio::drivers::bag

// DecodeMessage: one serialized message → the struct of its kind (message_decoder.h).

#include "swlio/drivers/bag/message_decoder.h"

namespace swlio::drivers::bag {
namespace {

// Legacy RslidarPacket sizes: CDR header 4 + Time 8 + 1248; ROS 1 Time 8 + 1248.
constexpr size_t kLegacyRslidarPacketCdrBytes = 1260;
constexpr size_t kLegacyRslidarPacketRos1Bytes = 1256;

RosMessageKind ResolveRslidarPacket(MessageEncoding encoding, size_t size) {
  const size_t legacy = encoding == MessageEncoding::kRos1 ? kLegacyRslidarPacketRos1Bytes
                                                           : kLegacyRslidarPacketCdrBytes;
  return size == legacy ? RosMessageKind::kRslidarPacketLegacy : RosMessageKind::kRslidarPacket;
}

bool DecodeAs(RosMessageKind kind, MessageReader& r, DecodedMessage* out) {
  switch (kind) {
    case RosMessageKind::kRslidarScan:
    case RosMessageKind::kRslidarPacketLegacy:
    case RosMessageKind::kRslidarPacket:
    case RosMessageKind::kRobosenseScan:
    case RosMessageKind::kVelodyneScan:
      return DecodeLidarPackets(kind, r, &out->packets);
    case RosMessageKind::kPointCloud2:
      return DecodePointCloud2(r, &out->cloud);
    case RosMessageKind::kImu:
      return DecodeImu(r, &out->imu);
    case RosMessageKind::kNavSatFix:
      return DecodeNavSatFix(r, &out->fix);
    case RosMessageKind::kOdometry:
      return DecodeOdometry(r, &out->odometry);
    case RosMessageKind::kTwistStamped:
      return DecodeTwistStamped(r, &out->twist);
    case RosMessageKind::kRslidarPacketEither:
    case RosMessageKind::kUnknown:
      break;
  }
  return false;
}

}  // namespace

bool DecodeMessage(RosMessageKind kind,
                   MessageEncoding encoding,
                   std::span<const uint8_t> bytes,
                   DecodedMessage* out,
                   std::string* error) {
  if (kind == RosMessageKind::kRslidarPacketEither)
    kind = ResolveRslidarPacket(encoding, bytes.size());
  out->kind = kind;
  if (kind == RosMessageKind::kUnknown) {
    *error = "not a message type swlio reads";
    return false;
  }
  MessageReader r;
  if (!r.Begin(bytes, encoding, error)) return false;
  if (DecodeAs(kind, r, out)) return true;
  *error = std::string(KindName(kind)) + ": " + r.Failure();
  return false;
}

std::optional<int64_t> HeaderStamp(const DecodedMessage& d) {
  switch (d.kind) {
    case RosMessageKind::kPointCloud2:
      return d.cloud.header.stamp_ns;
    case RosMessageKind::kImu:
      return d.imu.header.stamp_ns;
    case RosMessageKind::kNavSatFix:
      return d.fix.header.stamp_ns;
    case RosMessageKind::kOdometry:
      return d.odometry.header.stamp_ns;
    case RosMessageKind::kTwistStamped:
      return d.twist.header.stamp_ns;
    default:
      if (d.packets.has_header) return d.packets.header.stamp_ns;
      return std::nullopt;
  }
}

}  // namespace swlio::drivers::bag

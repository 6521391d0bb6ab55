// Message decoders: field offsets against the hand-computed XCDR1 layouts of
// research/bags.md §5 (cdr_layouts.out), CDR and ROS 1 round trips through the encoders, every
// truncation refused with a message, messages decoded as another type refused, and the topic
// classification (type names, the two RslidarPacket generations by definition, md5 or size).

#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <numeric>
#include <vector>

#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag {
namespace {

using Bytes = std::vector<uint8_t>;
constexpr auto kCdr = MessageEncoding::kCdr;
constexpr auto kRos1 = MessageEncoding::kRos1;

double F64At(const Bytes& b, size_t at) { return bytes::ReadF64Le(b.data() + at); }

ImuMsg SampleImu() {
  ImuMsg m;
  m.header = {1'700'000'000'123'456'789, "imu_link"};
  m.orientation = Eigen::Quaterniond(0.9, 0.1, -0.2, 0.3);
  m.angular_velocity_radps = {0.01, -0.02, 0.03};
  m.linear_acceleration_mps2 = {-0.08, -0.17, 9.82};
  std::iota(m.orientation_covariance.begin(), m.orientation_covariance.end(), 1.0);
  m.linear_acceleration_covariance[8] = 0.5;
  return m;
}

TEST(MessageDecoder, ImuLayoutMatchesTheResearchTable) {
  const ImuMsg m = SampleImu();
  const Bytes b = EncodeImu(m, kCdr);
  ASSERT_EQ(b.size(), 324u);
  EXPECT_EQ(F64At(b, 28), 0.1);    // orientation.x
  EXPECT_EQ(F64At(b, 52), 0.9);    // orientation.w
  EXPECT_EQ(F64At(b, 132), 0.01);  // angular_velocity.x
  EXPECT_EQ(F64At(b, 244), 9.82);  // linear_acceleration.z
  DecodedMessage d;
  std::string error;
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kImu, kCdr, b, &d, &error)) << error;
  EXPECT_EQ(d.imu.header.stamp_ns, m.header.stamp_ns);
  EXPECT_EQ(d.imu.header.frame_id, "imu_link");
  EXPECT_EQ(d.imu.orientation.coeffs(), m.orientation.coeffs());
  EXPECT_EQ(d.imu.angular_velocity_radps, m.angular_velocity_radps);
  EXPECT_EQ(d.imu.linear_acceleration_mps2, m.linear_acceleration_mps2);
  EXPECT_EQ(d.imu.orientation_covariance, m.orientation_covariance);
  EXPECT_EQ(d.imu.linear_acceleration_covariance, m.linear_acceleration_covariance);
}

TEST(MessageDecoder, Ros1ImuHasASeqAndNoPadding) {
  const ImuMsg m = SampleImu();
  const Bytes b = EncodeImu(m, kRos1);
  ASSERT_EQ(b.size(), 4u + 8 + 4 + 8 + 4 * 8 + 3 * 9 * 8 + 2 * 3 * 8);
  DecodedMessage d;
  std::string error;
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kImu, kRos1, b, &d, &error)) << error;
  EXPECT_EQ(d.imu.header.stamp_ns, m.header.stamp_ns);
  EXPECT_EQ(d.imu.linear_acceleration_mps2, m.linear_acceleration_mps2);
}

TEST(MessageDecoder, NavSatFixOdometryTwistLayouts) {
  NavSatFixMsg fix;
  fix.header = {1, "gnss"};
  fix.status = 2;
  fix.service = 9;
  fix.latitude_deg = 48.1;
  fix.longitude_deg = 11.5;
  fix.altitude_m = 520.0;
  fix.position_covariance_type = 2;
  const Bytes bf = EncodeNavSatFix(fix, kCdr);
  EXPECT_EQ(bf.size(), 128u);  // 125 + padding to 4
  EXPECT_EQ(F64At(bf, 28), 48.1);
  EXPECT_EQ(bf[124], 2);
  OdometryMsg odo;
  odo.header = {2, "map"};
  odo.child_frame_id = "base_link";
  odo.position_m = {1.5, 2.5, 3.5};
  odo.linear_velocity_mps = {0.7, 0, 0};
  odo.twist_covariance[35] = 4.0;
  const Bytes bo = EncodeOdometry(odo, kCdr);
  EXPECT_EQ(bo.size(), 716u);
  EXPECT_EQ(F64At(bo, 36), 1.5);
  EXPECT_EQ(F64At(bo, 380), 0.7);
  TwistStampedMsg tw;
  tw.header = {3, "base_link"};
  tw.linear_velocity_mps = {0.25, 0, 0};
  tw.angular_velocity_radps = {0, 0, -0.1};
  const Bytes bt = EncodeTwistStamped(tw, kCdr);
  EXPECT_EQ(bt.size(), 76u);
  EXPECT_EQ(F64At(bt, 28), 0.25);
  DecodedMessage d;
  std::string error;
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kNavSatFix, kCdr, bf, &d, &error)) << error;
  EXPECT_EQ(d.fix.status, 2);
  EXPECT_EQ(d.fix.service, 9);
  EXPECT_EQ(d.fix.altitude_m, 520.0);
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kOdometry, kCdr, bo, &d, &error)) << error;
  EXPECT_EQ(d.odometry.child_frame_id, "base_link");
  EXPECT_EQ(d.odometry.position_m, odo.position_m);
  EXPECT_EQ(d.odometry.twist_covariance[35], 4.0);
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kTwistStamped, kCdr, bt, &d, &error)) << error;
  EXPECT_EQ(d.twist.angular_velocity_radps.z(), -0.1);
}

PointCloud2Msg RslidarXyzirtCloud(const Bytes& data) {
  PointCloud2Msg c;
  c.header = {10, "rslidar"};
  c.height = 1;
  c.width = 1;
  c.fields = {{"x", 0, 7, 1},          {"y", 4, 7, 1},     {"z", 8, 7, 1},
              {"intensity", 12, 7, 1}, {"ring", 16, 4, 1}, {"timestamp", 18, 8, 1}};
  c.point_step = 26;
  c.row_step = 26;
  c.data = data;
  c.is_dense = true;
  return c;
}

TEST(MessageDecoder, PointCloud2LayoutMatchesTheResearchTable) {
  Bytes point(26);
  std::iota(point.begin(), point.end(), uint8_t{1});
  const Bytes b = EncodePointCloud2(RslidarXyzirtCloud(point), kCdr);
  EXPECT_EQ(b.size(), 220u);                         // 219 + padding
  EXPECT_EQ(bytes::ReadU32Le(b.data() + 188), 26u);  // data.count
  EXPECT_EQ(b[192], 1);                              // data[0]
  EXPECT_EQ(b[218], 1);                              // is_dense
  DecodedMessage d;
  std::string error;
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kPointCloud2, kCdr, b, &d, &error)) << error;
  ASSERT_EQ(d.cloud.fields.size(), 6u);
  EXPECT_EQ(d.cloud.fields[5].name, "timestamp");
  EXPECT_EQ(d.cloud.fields[5].offset, 18u);
  EXPECT_EQ(d.cloud.fields[5].datatype, 8);
  EXPECT_EQ(d.cloud.point_step, 26u);
  EXPECT_TRUE(std::equal(d.cloud.data.begin(), d.cloud.data.end(), point.begin(), point.end()));
  EXPECT_TRUE(d.cloud.is_dense);
}

TEST(MessageDecoder, NewRslidarPacketLayoutAndRole) {
  Bytes payload(1248, 0x5A);
  LidarPacketsMsg m;
  m.has_header = true;
  m.header = {77, "rslidar"};
  m.packets = {{77, payload, PacketRole::kInfo}};
  Bytes b;
  ASSERT_TRUE(EncodeLidarPackets(RosMessageKind::kRslidarPacket, m, kCdr, &b));
  EXPECT_EQ(b.size(), 1280u);
  EXPECT_EQ(b[24], 1);                                // is_difop
  EXPECT_EQ(bytes::ReadU32Le(b.data() + 28), 1248u);  // data length
  DecodedMessage d;
  std::string error;
  // Without a definition the size decides: 1280 is not the legacy 1260.
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kRslidarPacketEither, kCdr, b, &d, &error)) << error;
  EXPECT_EQ(d.kind, RosMessageKind::kRslidarPacket);
  ASSERT_EQ(d.packets.packets.size(), 1u);
  EXPECT_EQ(d.packets.packets[0].role, PacketRole::kInfo);
  EXPECT_EQ(d.packets.packets[0].stamp_ns, 77);
  EXPECT_EQ(d.packets.packets[0].payload.size(), 1248u);
  EXPECT_EQ(d.packets.header.frame_id, "rslidar");
}

TEST(MessageDecoder, VelodyneScanElementsAreFourAligned) {
  Bytes p0(1206, 0xEE);
  Bytes p1(1206, 0xFF);
  LidarPacketsMsg m;
  m.header = {5, "velodyne"};
  m.packets = {{1, p0, PacketRole::kUnstated}, {2, p1, PacketRole::kUnstated}};
  Bytes b;
  ASSERT_TRUE(EncodeLidarPackets(RosMessageKind::kVelodyneScan, m, kCdr, &b));
  // Header 4..24, 3 pad, count at 28, packet 0 at 32 (stamp) + 40 (data), stride 1216.
  EXPECT_EQ(bytes::ReadU32Le(b.data() + 28), 2u);
  EXPECT_EQ(b[40], 0xEE);
  EXPECT_EQ(bytes::ReadU32Le(b.data() + 36 + 1216), 2u);  // packets[1].stamp.nanosec
  EXPECT_EQ(b[40 + 1216], 0xFF);
  DecodedMessage d;
  std::string error;
  ASSERT_TRUE(DecodeMessage(RosMessageKind::kVelodyneScan, kCdr, b, &d, &error)) << error;
  ASSERT_EQ(d.packets.packets.size(), 2u);
  EXPECT_EQ(d.packets.packets[1].stamp_ns, 2);
  EXPECT_EQ(d.packets.packets[1].payload[0], 0xFF);
}

/// One encoded message per decodable kind, in CDR or ROS 1.
std::vector<std::pair<RosMessageKind, Bytes>> AllKinds(MessageEncoding e) {
  static const Bytes rs(1248, 1);
  static const Bytes vl(1206, 2);
  static const Bytes pt(26, 3);
  std::vector<std::pair<RosMessageKind, Bytes>> out;
  const auto packets = [&](RosMessageKind k, const Bytes& p, size_t n) {
    LidarPacketsMsg m;
    m.header = {9, "lidar"};
    for (size_t i = 0; i < n; ++i) m.packets.push_back({int64_t(i), p, PacketRole::kData});
    Bytes b;
    EXPECT_TRUE(EncodeLidarPackets(k, m, e, &b));
    out.emplace_back(k, b);
  };
  packets(RosMessageKind::kRslidarScan, rs, 2);
  packets(RosMessageKind::kRslidarPacketLegacy, rs, 1);
  packets(RosMessageKind::kRslidarPacket, rs, 1);
  packets(RosMessageKind::kRobosenseScan, rs, 2);
  packets(RosMessageKind::kVelodyneScan, vl, 2);
  out.emplace_back(RosMessageKind::kPointCloud2, EncodePointCloud2(RslidarXyzirtCloud(pt), e));
  out.emplace_back(RosMessageKind::kImu, EncodeImu(SampleImu(), e));
  NavSatFixMsg fix;
  fix.header = {1, "gnss"};
  out.emplace_back(RosMessageKind::kNavSatFix, EncodeNavSatFix(fix, e));
  OdometryMsg odo;
  odo.header = {1, "odom"};
  odo.child_frame_id = "base_link";
  out.emplace_back(RosMessageKind::kOdometry, EncodeOdometry(odo, e));
  TwistStampedMsg tw;
  tw.header = {1, "base_link"};
  out.emplace_back(RosMessageKind::kTwistStamped, EncodeTwistStamped(tw, e));
  return out;
}

TEST(MessageDecoder, EveryTruncationFailsWithAMessage) {
  for (const MessageEncoding e : {kCdr, kRos1}) {
    for (const auto& [kind, bytes] : AllKinds(e)) {
      DecodedMessage d;
      std::string error;
      ASSERT_TRUE(DecodeMessage(kind, e, bytes, &d, &error)) << KindName(kind) << ": " << error;
      // CDR keeps up to 3 padding bytes, so a cut inside them still decodes.
      const size_t unpadded_min = e == kCdr ? bytes.size() - 3 : bytes.size();
      for (size_t n = 0; n < unpadded_min; ++n) {
        const std::span<const uint8_t> cut(bytes.data(), n);
        error.clear();
        if (DecodeMessage(kind, e, cut, &d, &error)) continue;  // ended in the padding
        EXPECT_FALSE(error.empty()) << KindName(kind) << " cut at " << n;
      }
      const std::span<const uint8_t> half(bytes.data(), bytes.size() / 2);
      EXPECT_FALSE(DecodeMessage(kind, e, half, &d, &error)) << KindName(kind);
    }
  }
}

TEST(MessageDecoder, AMessageOfAnotherTypeIsRefused) {
  for (const MessageEncoding e : {kCdr, kRos1}) {
    const auto all = AllKinds(e);
    for (const auto& [declared, unused] : all) {
      for (const auto& [actual, bytes] : all) {
        if (declared == actual) continue;
        DecodedMessage d;
        std::string error;
        EXPECT_FALSE(DecodeMessage(declared, e, bytes, &d, &error))
            << KindName(actual) << " decoded as " << KindName(declared)
            << (e == kCdr ? " (CDR)" : " (ROS 1)");
      }
    }
  }
}

TEST(MessageDecoder, ClassifiesTypesAndRslidarGenerations) {
  BagTopic t;
  t.type = "sensor_msgs/msg/Imu";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kImu);
  t.type = "sensor_msgs/Imu";  // ROS 1 spelling
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kImu);
  t.type = "rslidar_msgs/rslidarScan";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kRslidarScan);
  t.type = "std_msgs/msg/String";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kUnknown);
  t.type = "rslidar_msg/msg/RslidarPacket";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kRslidarPacketEither);
  t.definition = "std_msgs/Header header\nuint8 is_difop\nuint8 is_frame_begin\nuint8[] data\n";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kRslidarPacket);
  t.definition = "builtin_interfaces/Time stamp\nuint8[1248] data\n";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kRslidarPacketLegacy);
  t.definition.clear();
  t.type = "rslidar_msg/RslidarPacket";
  t.md5sum = "4b1cc155a9097c0cb935a7abf46d6eef";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kRslidarPacket);
  t.md5sum = "1e4288e00b9222ea477b73350bf24f51";
  EXPECT_EQ(ClassifyTopic(t), RosMessageKind::kRslidarPacketLegacy);
}

TEST(MessageDecoder, UnknownKindIsAnErrorNotACrash) {
  DecodedMessage d;
  std::string error;
  const Bytes b = {0, 1, 0, 0};
  EXPECT_FALSE(DecodeMessage(RosMessageKind::kUnknown, kCdr, b, &d, &error));
  EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace swlio::drivers::bag

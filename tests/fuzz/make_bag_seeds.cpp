// Seeds for the bag fuzz targets (mcap_fuzz, ros1bag_fuzz, bag_message_fuzz), written with
// swlio's own encoders and writers:
//   - always: one synthetic message of every kind (CDR and ROS 1), and small MCAP files (none,
//     zstd, lz4; with and without summary; unchunked) and ROS 1 bags (none, bz2, lz4; closed
//     and unclosed) holding them — the kept corpora under tests/fuzz/corpus/ are this output;
//   - always: an MCAP laid out as `swlio-bag export` writes one (ros2msg schema texts, QoS-less
//     channels, an rslidar_sdk cloud of a short sweep, Imu, /tf_static);
//   - with DATA_DIR: the same from the first messages of each real .db3 bag (LiDAR messages cut
//     to 3 packets), which scripts/fuzz adds at run time (real data stays out of the repo).
// Usage: make_bag_seeds OUT_DIR [DATA_DIR]   (writes OUT_DIR/{mcap,ros1bag,bag_message}/)

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "ros1_bag_writer.h"  // tests/drivers/support
#include "swlio/drivers/bag/bag_open.h"
#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "swlio/drivers/bag/point_cloud_writer.h"
#include "swlio/drivers/bag/ros2msg_schema.h"

namespace {

namespace fs = std::filesystem;
namespace bag = swlio::drivers::bag;
using Bytes = std::vector<uint8_t>;

/// One message of one topic, in both encodings.
struct Sample {
  std::string topic;
  std::string type;  ///< ROS 2 spelling
  bag::RosMessageKind kind;
  int64_t t_ns;
  Bytes cdr;
  Bytes ros1;
};

void Write(const fs::path& path, const Bytes& b) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

/// Both encodings of a decoded message of `kind` (false for kinds without an encoder).
bool Encode(bag::RosMessageKind kind, const bag::DecodedMessage& d, Sample* s) {
  for (const auto e : {bag::MessageEncoding::kCdr, bag::MessageEncoding::kRos1}) {
    Bytes& out = e == bag::MessageEncoding::kCdr ? s->cdr : s->ros1;
    switch (kind) {
      case bag::RosMessageKind::kImu:
        out = bag::EncodeImu(d.imu, e);
        break;
      case bag::RosMessageKind::kNavSatFix:
        out = bag::EncodeNavSatFix(d.fix, e);
        break;
      case bag::RosMessageKind::kOdometry:
        out = bag::EncodeOdometry(d.odometry, e);
        break;
      case bag::RosMessageKind::kTwistStamped:
        out = bag::EncodeTwistStamped(d.twist, e);
        break;
      case bag::RosMessageKind::kPointCloud2:
        out = bag::EncodePointCloud2(d.cloud, e);
        break;
      default:
        if (!bag::EncodeLidarPackets(kind, d.packets, e, &out)) return false;
    }
  }
  return true;
}

std::vector<Sample> Synthetic() {
  static const Bytes rs(1248, 0x55);
  static const Bytes vl(1206, 0xEE);
  static Bytes point(26, 0);
  std::vector<Sample> out;
  const int64_t t = 1'700'000'000'000'000'000;
  bag::DecodedMessage d;
  d.packets.header = {t, "lidar"};
  d.packets.packets = {{t, rs, bag::PacketRole::kData}, {t + 1000, rs, bag::PacketRole::kInfo}};
  const auto add = [&](const char* topic, const char* type, bag::RosMessageKind k) {
    Sample s{topic, type, k, t + static_cast<int64_t>(out.size()), {}, {}};
    if (Encode(k, d, &s)) out.push_back(s);
  };
  add("/rslidar_packets", "rslidar_msg/msg/RslidarScan", bag::RosMessageKind::kRslidarScan);
  add("/robosense_packets", "robosense_msgs/msg/RobosenseScan",
      bag::RosMessageKind::kRobosenseScan);
  d.packets.packets.resize(1);
  add("/rslidar_packets_difop", "rslidar_msgs/msg/rslidarPacket",
      bag::RosMessageKind::kRslidarPacketLegacy);
  add("/rslidar_packet", "rslidar_msg/msg/RslidarPacket", bag::RosMessageKind::kRslidarPacket);
  d.packets.packets = {{t, vl, bag::PacketRole::kUnstated}};
  add("/velodyne_packets", "velodyne_msgs/msg/VelodyneScan", bag::RosMessageKind::kVelodyneScan);
  d.cloud.header = {t, "rslidar"};
  d.cloud.height = 1;
  d.cloud.width = 1;
  d.cloud.fields = {{"x", 0, 7, 1},          {"y", 4, 7, 1},     {"z", 8, 7, 1},
                    {"intensity", 12, 7, 1}, {"ring", 16, 4, 1}, {"timestamp", 18, 8, 1}};
  d.cloud.point_step = 26;
  d.cloud.row_step = 26;
  d.cloud.data = point;
  add("/points", "sensor_msgs/msg/PointCloud2", bag::RosMessageKind::kPointCloud2);
  d.imu.header = {t, "imu_link"};
  add("/imu/data", "sensor_msgs/msg/Imu", bag::RosMessageKind::kImu);
  d.fix.header = {t, "gnss"};
  add("/fix", "sensor_msgs/msg/NavSatFix", bag::RosMessageKind::kNavSatFix);
  d.odometry.header = {t, "odom"};
  d.odometry.child_frame_id = "base_link";
  add("/odom", "nav_msgs/msg/Odometry", bag::RosMessageKind::kOdometry);
  d.twist.header = {t, "base_link"};
  add("/twist", "geometry_msgs/msg/TwistStamped", bag::RosMessageKind::kTwistStamped);
  return out;
}

/// The first `per_topic` messages of each topic of a real bag, LiDAR messages cut to 3 packets.
std::vector<Sample> FromBag(const std::string& path, size_t per_topic) {
  std::vector<Sample> out;
  std::string error;
  auto reader = bag::OpenBag(path, {}, &error);
  if (!reader) return out;
  std::vector<size_t> taken(reader->topics().size(), 0);
  bag::BagMessage m;
  bag::DecodedMessage d;
  while (reader->Next(&m)) {
    const bag::BagTopic& t = reader->topics()[m.topic];
    if (taken[m.topic]++ >= per_topic) continue;
    bag::RosMessageKind kind = bag::ClassifyTopic(t);
    if (!bag::DecodeMessage(kind, t.encoding, m.data, &d, &error)) continue;
    kind = d.kind;  // a resolved RslidarPacket generation
    if (d.packets.packets.size() > 3) d.packets.packets.resize(3);
    Sample s{t.name, t.type, kind, m.log_time_ns, {}, {}};
    if (Encode(kind, d, &s)) out.push_back(s);
  }
  return out;
}

/// An exported recording's messages in miniature: /tf_static, a 12-point rslidar_sdk cloud,
/// two Imu samples (kinds without an encoder for ROS 1 keep only their CDR).
std::vector<Sample> ExportStyle() {
  std::vector<Sample> out;
  const int64_t t = 1'764'000'000'000'000'000;
  const auto cdr = bag::MessageEncoding::kCdr;
  bag::TransformStampedMsg tf;
  tf.header = {t, "imu_link"};
  tf.child_frame_id = "rslidar";
  tf.translation_m = {0.1, 0.0, 0.2};
  const std::vector<bag::TransformStampedMsg> tfs = {tf};
  out.push_back({"/tf_static",
                 "tf2_msgs/msg/TFMessage",
                 bag::RosMessageKind::kUnknown,
                 t,
                 bag::EncodeTfMessage(tfs, cdr),
                 {}});
  swlio::Scan scan;
  scan.t_start_ns = t;
  for (int i = 0; i < 12; ++i) {
    swlio::LidarPoint p;
    p.xyz_m = {1.0f + static_cast<float>(i), 0.5f, -0.2f};
    p.ring = static_cast<uint16_t>(i % 16);
    p.dt_ns = i * 3456;
    scan.points.push_back(p);
  }
  bag::OwnedPointCloud2 cloud;
  bag::RslidarCloudFromScan(scan, "rslidar", &cloud);
  out.push_back({"/rslidar_points", "sensor_msgs/msg/PointCloud2",
                 bag::RosMessageKind::kPointCloud2, t + 100'000'000,
                 bag::EncodePointCloud2(cloud.msg, cdr),
                 bag::EncodePointCloud2(cloud.msg, bag::MessageEncoding::kRos1)});
  for (int i = 0; i < 2; ++i) {
    bag::ImuMsg imu;
    imu.header = {t + i * 5'000'000, "imu_link"};
    imu.orientation_covariance[0] = -1.0;
    imu.linear_acceleration_mps2 = {0.0, 0.0, 9.81};
    out.push_back({"/imu/data", "sensor_msgs/msg/Imu", bag::RosMessageKind::kImu,
                   imu.header.stamp_ns, bag::EncodeImu(imu, cdr),
                   bag::EncodeImu(imu, bag::MessageEncoding::kRos1)});
  }
  return out;
}

/// The exported-style samples as `swlio-bag export` writes them: schemas with their texts.
Bytes ExportStyleMcap(const std::vector<Sample>& samples) {
  auto w = bag::McapWriter::CreateInMemory({});
  std::map<std::string, uint16_t> channels;
  for (const Sample& s : samples) {
    auto [it, added] = channels.emplace(s.topic, 0);
    if (added) {
      it->second = w->AddChannel(w->AddSchema(s.type, "ros2msg", bag::Ros2MsgSchema(s.type)),
                                 s.topic, "cdr");
    }
    w->Write(it->second, s.t_ns, s.t_ns, s.cdr);
  }
  std::string error;
  w->Close(&error);
  return w->bytes();
}

Bytes Mcap(const std::vector<Sample>& samples, bag::Compression c, bool summary, uint64_t chunk) {
  bag::McapWriterOptions o;
  o.compression = c;
  o.summary = summary;
  o.chunk_bytes = chunk;
  auto w = bag::McapWriter::CreateInMemory(o);
  std::map<std::string, uint16_t> channels;
  for (const Sample& s : samples) {
    auto [it, added] = channels.emplace(s.topic, 0);
    if (added) it->second = w->AddChannel(w->AddSchema(s.type, "ros2msg", ""), s.topic, "cdr");
    w->Write(it->second, s.t_ns, s.t_ns, s.cdr);
  }
  std::string error;
  w->Close(&error);
  return w->bytes();
}

void WriteRos1Bags(const fs::path& dir,
                   const std::string& tag,
                   const std::vector<Sample>& samples) {
  for (const char* compression : {"none", "bz2", "lz4"}) {
    for (const bool closed : {true, false}) {
      swlio::test::Ros1BagWriter w(compression, 4096);
      std::map<std::string, uint32_t> connections;
      for (const Sample& s : samples) {
        auto [it, added] = connections.emplace(s.topic, static_cast<uint32_t>(connections.size()));
        if (added) w.AddConnection({it->second, s.topic, bag::NormalizeTypeName(s.type), "*", ""});
        w.Write(it->second, s.t_ns, s.ros1);
      }
      Write(dir / (tag + "_" + compression + (closed ? "" : "_unclosed") + ".bag"),
            w.Finish(closed));
    }
  }
}

void WriteSet(const fs::path& out, const std::string& tag, const std::vector<Sample>& samples) {
  if (samples.empty()) return;
  for (size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    Bytes cdr = {static_cast<uint8_t>(s.kind)};
    cdr.insert(cdr.end(), s.cdr.begin(), s.cdr.end());
    Write(out / "bag_message" / (tag + "_cdr" + std::to_string(i)), cdr);
    Bytes ros1 = {static_cast<uint8_t>(0x80 | static_cast<uint8_t>(s.kind))};
    ros1.insert(ros1.end(), s.ros1.begin(), s.ros1.end());
    Write(out / "bag_message" / (tag + "_ros1_" + std::to_string(i)), ros1);
  }
  Write(out / "mcap" / (tag + "_none.mcap"), Mcap(samples, bag::Compression::kNone, true, 4096));
  Write(out / "mcap" / (tag + "_zstd.mcap"), Mcap(samples, bag::Compression::kZstd, true, 4096));
  Write(out / "mcap" / (tag + "_lz4_nosummary.mcap"),
        Mcap(samples, bag::Compression::kLz4Frame, false, 4096));
  Write(out / "mcap" / (tag + "_unchunked.mcap"), Mcap(samples, bag::Compression::kNone, false, 0));
  WriteRos1Bags(out / "ros1bag", tag, samples);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_bag_seeds OUT_DIR [DATA_DIR]\n");
    return 2;
  }
  const fs::path out = argv[1];
  WriteSet(out, "synthetic", Synthetic());
  Write(out / "mcap" / "export_style.mcap", ExportStyleMcap(ExportStyle()));
  if (argc > 2) {
    const fs::path data = argv[2];
    const std::pair<const char*, const char*> bags[] = {{"rs16", "rs16_washing_house"},
                                                        {"vlp16", "velodyne_nebula/vlp16"},
                                                        {"vlp32", "velodyne_nebula/vlp32"},
                                                        {"helios16p", "rs_helios16p_nebula"}};
    for (const auto& [tag, dir] : bags) WriteSet(out, tag, FromBag((data / dir).string(), 2));
  }
  std::printf("bag seeds in %s\n", out.c_str());
  return 0;
}

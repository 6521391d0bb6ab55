// The four real rosbag2 .db3 files of shared/data against their README and their repackaged
// pcaps: topic names, types and counts as the README lists them, and every LiDAR payload the
// bag yields byte-identical, in order, to the UDP payloads of the pcap made from the same bag.
// For the RS-LiDAR-16 bag the payloads also go through swlio's RS16 decoder: the same returns
// with the same coordinates, and the README's count of valid returns (1,063,236).

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "bag_test_util.h"
#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/rosbag2_sqlite_reader.h"
#include "swlio/drivers/rs16_decoder.h"
#include "test_data.h"

namespace swlio::drivers::bag {
namespace {

using test::Payload;

constexpr char kRs16Bag[] = "rs16_washing_house/rosbag2_2022_08_16-11_55_30_0.db3";
constexpr char kRs16Pcap[] = "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap";

std::unique_ptr<Rosbag2SqliteReader> OpenDb3(const std::filesystem::path& path) {
  std::string error;
  auto reader = Rosbag2SqliteReader::Open(path.string(), {}, &error);
  EXPECT_NE(reader, nullptr) << error;
  return reader;
}

/// Every LiDAR payload of the bag in bag order, split by role (MSOP/data vs DIFOP/info; a
/// packet without a stated role is classified by its first bytes, RoboSense DIFOP A5 FF).
struct BagPayloads {
  std::vector<std::vector<uint8_t>> data;
  std::vector<std::vector<uint8_t>> info;
  std::vector<int64_t> scan_log_times_ns;  ///< log time of each multi-packet message
  size_t decode_failures = 0;
};

BagPayloads ReadPayloads(BagReader& reader) {
  BagPayloads out;
  std::vector<RosMessageKind> kinds;
  for (const BagTopic& t : reader.topics()) kinds.push_back(ClassifyTopic(t));
  DecodedMessage decoded;
  BagMessage m;
  std::string error;
  while (reader.Next(&m)) {
    const BagTopic& topic = reader.topics()[m.topic];
    if (!DecodeMessage(kinds[m.topic], topic.encoding, m.data, &decoded, &error)) {
      ADD_FAILURE() << topic.name << " #" << m.index << ": " << error;
      ++out.decode_failures;
      continue;
    }
    if (decoded.packets.packets.size() > 1) out.scan_log_times_ns.push_back(m.log_time_ns);
    for (const LidarPacketView& p : decoded.packets.packets) {
      const bool info =
          p.role == PacketRole::kInfo ||
          (p.role == PacketRole::kUnstated && p.payload[0] == 0xA5 && p.payload[1] == 0xFF);
      (info ? out.info : out.data).emplace_back(p.payload.begin(), p.payload.end());
    }
  }
  EXPECT_EQ(reader.error(), "");
  return out;
}

std::vector<std::vector<uint8_t>> PortPayloads(const std::vector<Payload>& all, uint16_t port) {
  std::vector<std::vector<uint8_t>> out;
  for (const Payload& p : all) {
    if (p.dst_port == port) out.push_back(p.bytes);
  }
  return out;
}

/// Same sequence, compared packet by packet so a failure names the first difference.
void ExpectSamePackets(const std::vector<std::vector<uint8_t>>& bag,
                       const std::vector<std::vector<uint8_t>>& pcap) {
  ASSERT_EQ(bag.size(), pcap.size());
  for (size_t i = 0; i < bag.size(); ++i) ASSERT_EQ(bag[i], pcap[i]) << "packet " << i;
}

TEST(Rosbag2RealBags, WashingHouseTopicsAndCountsMatchTheReadme) {
  SWLIO_REQUIRE_DATA(path, kRs16Bag);
  auto reader = OpenDb3(path);
  ASSERT_NE(reader, nullptr);
  EXPECT_EQ(reader->db_schema_version(), 2);  // Foxy/Galactic layout: no schema table
  ASSERT_EQ(reader->topics().size(), 2u);
  const BagTopic& difop = reader->topics()[0];
  const BagTopic& msop = reader->topics()[1];
  EXPECT_EQ(difop.name, "/rslidar_packets_difop");
  EXPECT_EQ(difop.type, "rslidar_msg/msg/RslidarPacket");
  EXPECT_EQ(msop.name, "/rslidar_packets");
  EXPECT_EQ(msop.type, "rslidar_msg/msg/RslidarScan");
  EXPECT_EQ(ClassifyTopic(msop), RosMessageKind::kRslidarScan);
  EXPECT_EQ(ClassifyTopic(difop), RosMessageKind::kRslidarPacketEither);  // no definition stored
  for (const BagTopic& t : reader->topics()) {
    EXPECT_EQ(t.message_count, 40u) << t.name;
    EXPECT_EQ(t.encoding, MessageEncoding::kCdr);
  }
  // metadata.yaml: starting_time 1660622130216597059, duration 3903138038 ns.
  EXPECT_EQ(difop.first_log_time_ns, 1660622130216597059);
  EXPECT_EQ(std::max(difop.last_log_time_ns, msop.last_log_time_ns) - difop.first_log_time_ns,
            3903138038);
  const auto all = test::ReadAll(*reader);
  ASSERT_EQ(all.size(), 80u);
  for (size_t i = 1; i < all.size(); ++i) EXPECT_LE(all[i - 1].log_time_ns, all[i].log_time_ns);
  EXPECT_EQ(all.front().data.size(), 1260u);  // research/bags.md §2.2
  EXPECT_EQ(reader->stats().messages_returned, 80u);
  EXPECT_EQ(reader->stats().messages_skipped, 0u);
}

TEST(Rosbag2RealBags, WashingHousePayloadsAreThePcapsBytesInOrder) {
  SWLIO_REQUIRE_DATA(bag_path, kRs16Bag);
  SWLIO_REQUIRE_DATA(pcap_path, kRs16Pcap);
  auto reader = OpenDb3(bag_path);
  ASSERT_NE(reader, nullptr);
  const BagPayloads bag = ReadPayloads(*reader);
  const std::vector<Payload> pcap = test::PcapPayloads(pcap_path);
  EXPECT_EQ(bag.decode_failures, 0u);
  ExpectSamePackets(bag.data, PortPayloads(pcap, 2244));  // 3,000 MSOP
  ExpectSamePackets(bag.info, PortPayloads(pcap, 7788));  // 40 DIFOP
  EXPECT_EQ(bag.data.size(), 3000u);
  // The README: each scan's last MSOP record is stamped with the scan's bag receive time (the
  // pcap keeps microseconds, some rounded either way).
  ASSERT_EQ(bag.scan_log_times_ns.size(), 40u);
  std::vector<int64_t> msop_times;
  for (const Payload& p : pcap) {
    if (p.dst_port == 2244) msop_times.push_back(p.t_ns);
  }
  for (size_t s = 0; s < 40; ++s) {
    EXPECT_LE(std::abs(msop_times[75 * s + 74] - bag.scan_log_times_ns[s]), 1000) << "scan " << s;
  }
}

TEST(Rosbag2RealBags, WashingHouseDecodesToThePointsOfItsPcap) {
  SWLIO_REQUIRE_DATA(bag_path, kRs16Bag);
  SWLIO_REQUIRE_DATA(pcap_path, kRs16Pcap);
  auto reader = OpenDb3(bag_path);
  ASSERT_NE(reader, nullptr);
  const BagPayloads bag = ReadPayloads(*reader);
  const std::vector<Payload> pcap = test::PcapPayloads(pcap_path);
  const auto pcap_msop = PortPayloads(pcap, 2244);
  const auto pcap_difop = PortPayloads(pcap, 7788);
  ASSERT_FALSE(bag.info.empty());
  ASSERT_FALSE(pcap_difop.empty());
  LidarConfig config;
  config.min_range_m = 0.0;
  config.max_range_m = 400.0;
  Rs16Decoder from_bag(config);
  Rs16Decoder from_pcap(config);
  from_bag.DecodeInfo(bag.info.front());
  from_pcap.DecodeInfo(pcap_difop.front());
  ASSERT_EQ(bag.data.size(), pcap_msop.size());
  static LidarPacketDecoder::ReturnBuffer a;
  static LidarPacketDecoder::ReturnBuffer b;
  uint64_t points = 0;
  for (size_t i = 0; i < bag.data.size(); ++i) {
    LidarPacketSummary sa;
    LidarPacketSummary sb;
    ASSERT_EQ(from_bag.DecodeData(bag.data[i], a, &sa), DecodeStatus::kOk) << i;
    ASSERT_EQ(from_pcap.DecodeData(pcap_msop[i], b, &sb), DecodeStatus::kOk) << i;
    ASSERT_EQ(sa.returns, sb.returns) << i;
    ASSERT_EQ(sa.t_sensor_ns, sb.t_sensor_ns) << i;
    for (uint32_t k = 0; k < sa.returns; ++k) {
      ASSERT_EQ(a[k].x_m, b[k].x_m);
      ASSERT_EQ(a[k].y_m, b[k].y_m);
      ASSERT_EQ(a[k].z_m, b[k].z_m);
      ASSERT_EQ(a[k].ring, b[k].ring);
    }
    points += sa.returns;
  }
  EXPECT_EQ(points, 1'063'236u);  // the README's count of valid returns
}

struct NebulaBag {
  const char* bag;
  const char* pcap;
  const char* topic;
  const char* type;
  uint64_t messages;
  uint16_t data_port;
  uint16_t info_port;  ///< 0: none
  size_t data_packets;
};

class Rosbag2NebulaBags : public ::testing::TestWithParam<NebulaBag> {};

TEST_P(Rosbag2NebulaBags, PayloadsAreThePcapsBytesInOrder) {
  const NebulaBag& c = GetParam();
  SWLIO_REQUIRE_DATA(bag_path, c.bag);
  SWLIO_REQUIRE_DATA(pcap_path, c.pcap);
  auto reader = OpenDb3(bag_path);
  ASSERT_NE(reader, nullptr);
  EXPECT_EQ(reader->db_schema_version(), 3);
  EXPECT_EQ(reader->ros_distro(), "humble");
  ASSERT_EQ(reader->topics().size(), 1u);
  EXPECT_EQ(reader->topics()[0].name, c.topic);
  EXPECT_EQ(reader->topics()[0].type, c.type);
  EXPECT_EQ(reader->topics()[0].message_count, c.messages);
  const BagPayloads bag = ReadPayloads(*reader);
  const std::vector<Payload> pcap = test::PcapPayloads(pcap_path);
  EXPECT_EQ(bag.data.size(), c.data_packets);
  ExpectSamePackets(bag.data, PortPayloads(pcap, c.data_port));
  if (c.info_port != 0) ExpectSamePackets(bag.info, PortPayloads(pcap, c.info_port));
}

INSTANTIATE_TEST_SUITE_P(
    Nebula,
    Rosbag2NebulaBags,
    ::testing::Values(NebulaBag{"velodyne_nebula/vlp16/1673400471837873222_0.db3",
                                "velodyne_nebula/vlp16/vlp16_port2368.repackaged.pcap",
                                "/velodyne_packets", "velodyne_msgs/msg/VelodyneScan", 4, 2368, 0,
                                603},
                      NebulaBag{"velodyne_nebula/vlp32/1713492677464078412_0.db3",
                                "velodyne_nebula/vlp32/vlp32_port2368.repackaged.pcap",
                                "/sensing/lidar/front/velodyne_packets",
                                "velodyne_msgs/msg/VelodyneScan", 5, 2368, 0, 379},
                      NebulaBag{"rs_helios16p_nebula/rosbag2_2023_08_03-11_02_46_0.db3",
                                "rs_helios16p_nebula/helios16p_msop6699_difop7788.repackaged.pcap",
                                "/robosense_packets", "robosense_msgs/msg/RobosenseScan", 5, 6699,
                                7788, 750}));

}  // namespace
}  // namespace swlio::drivers::bag

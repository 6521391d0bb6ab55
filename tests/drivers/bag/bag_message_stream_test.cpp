// The decoded stream: topics chosen by type (and by name when several fit), the real
// washing_house bag as swlio input, and every kind of bad message skipped, counted and named.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "swlio/drivers/bag/bag_message_stream.h"
#include "swlio/drivers/bag/bag_open.h"
#include "swlio/drivers/bag/mcap_reader.h"
#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "test_data.h"

namespace swlio::drivers::bag {
namespace {

using Bytes = std::vector<uint8_t>;
constexpr auto kCdr = MessageEncoding::kCdr;
constexpr int64_t kT0 = 1'700'000'000'000'000'000;

std::vector<BagTopic> Topics(const std::vector<std::pair<std::string, std::string>>& nt) {
  std::vector<BagTopic> out;
  for (const auto& [name, type] : nt) {
    BagTopic t;
    t.name = name;
    t.type = type;
    out.push_back(t);
  }
  return out;
}

TEST(TopicSelection, ByTypeWithTheDifopCompanion) {
  const auto topics = Topics({{"/rslidar_packets_difop", "rslidar_msg/msg/RslidarPacket"},
                              {"/rslidar_packets", "rslidar_msg/msg/RslidarScan"},
                              {"/imu/data", "sensor_msgs/msg/Imu"},
                              {"/fix", "sensor_msgs/msg/NavSatFix"},
                              {"/chatter", "std_msgs/msg/String"}});
  SelectedTopics s;
  std::string error;
  ASSERT_TRUE(SelectTopics(topics, {}, &s, &error)) << error;
  EXPECT_EQ(s.lidar, 1u);
  EXPECT_EQ(s.lidar_info, 0u);
  EXPECT_EQ(s.imu, 2u);
  EXPECT_EQ(s.gnss, 3u);
  EXPECT_FALSE(s.wheel.has_value());
}

TEST(TopicSelection, SeveralCandidatesNeedAName) {
  const auto topics = Topics({{"/imu/data", "sensor_msgs/msg/Imu"},
                              {"/imu/raw", "sensor_msgs/msg/Imu"},
                              {"/odom", "nav_msgs/msg/Odometry"}});
  SelectedTopics s;
  std::string error;
  EXPECT_FALSE(SelectTopics(topics, {}, &s, &error));
  EXPECT_NE(error.find("/imu/data /imu/raw"), std::string::npos) << error;
  EXPECT_NE(error.find("--imu-topic"), std::string::npos) << error;
  TopicChoice choice;
  choice.imu = "/imu/raw";
  ASSERT_TRUE(SelectTopics(topics, choice, &s, &error)) << error;
  EXPECT_EQ(s.imu, 1u);
  EXPECT_EQ(s.wheel, 2u);
  choice.imu = "/odom";  // not an IMU type
  EXPECT_FALSE(SelectTopics(topics, choice, &s, &error));
  EXPECT_NE(error.find("is no IMU topic"), std::string::npos) << error;
  choice.imu = "/nothing";
  EXPECT_FALSE(SelectTopics(topics, choice, &s, &error));
  EXPECT_NE(error.find("no topic /nothing"), std::string::npos) << error;
}

TEST(BagMessageStream, WashingHouseDeliversEveryScanAndDifop) {
  SWLIO_REQUIRE_DATA(dir, "rs16_washing_house/metadata.yaml");
  std::string error;
  auto reader = OpenBag(dir.parent_path().string(), {}, &error);
  ASSERT_NE(reader, nullptr) << error;
  auto stream = BagMessageStream::Create(std::move(reader), {}, &error);
  ASSERT_NE(stream, nullptr) << error;
  StreamMessage m;
  size_t packets = 0;
  size_t messages = 0;
  int64_t last_log = 0;
  while (stream->Next(&m)) {
    EXPECT_EQ(m.role, TopicRole::kLidar);
    EXPECT_GE(m.log_time_ns, last_log);
    last_log = m.log_time_ns;
    packets += m.decoded->packets.packets.size();
    ++messages;
  }
  EXPECT_EQ(messages, 80u);
  EXPECT_EQ(packets, 3040u);
  EXPECT_TRUE(stream->warnings().empty());
  EXPECT_EQ(stream->topic_stats(*stream->selected().lidar).delivered, 40u);
}

/// An MCAP with an IMU topic holding one of each kind of bad message between good ones, and a
/// cloud topic with a NaN point and an empty cloud.
Bytes BadMessagesMcap() {
  McapWriterOptions o;
  auto w = McapWriter::CreateInMemory(o);
  const uint16_t imu =
      w->AddChannel(w->AddSchema("sensor_msgs/msg/Imu", "ros2msg", ""), "/imu", "cdr");
  const uint16_t pts =
      w->AddChannel(w->AddSchema("sensor_msgs/msg/PointCloud2", "ros2msg", ""), "/points", "cdr");
  const auto write_imu = [&](int64_t log, int64_t stamp) {
    ImuMsg m;
    m.header = {stamp, "imu_link"};
    w->Write(imu, log, log, EncodeImu(m, kCdr));
  };
  write_imu(kT0 + 10, kT0 + 10);  // #0 good
  write_imu(kT0 + 20, kT0 + 20);  // #1 good
  write_imu(kT0 + 30, kT0 + 15);  // #2 out of order
  write_imu(kT0 + 40, kT0 + 20);  // #3 duplicate
  write_imu(kT0 + 50, 0);         // #4 zero stamp
  Bytes cut = EncodeImu(ImuMsg{}, kCdr);
  cut.resize(100);
  w->Write(imu, kT0 + 60, kT0 + 60, cut);  // #5 does not decode
  write_imu(kT0 + 70, kT0 + 70);           // #6 good
  PointCloud2Msg c;
  c.header = {kT0 + 5, "lidar"};
  c.height = 1;
  c.width = 2;
  c.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}};
  c.point_step = 12;
  c.row_step = 24;
  Bytes data(24, 0);
  data[3] = 0x7F;  // x of point 0 = NaN (0x7FC00000)
  data[2] = 0xC0;
  c.data = data;
  w->Write(pts, kT0 + 5, kT0 + 5, EncodePointCloud2(c, kCdr));  // #0: one good point
  c.header.stamp_ns = kT0 + 25;
  c.width = 0;
  c.row_step = 0;
  w->Write(pts, kT0 + 25, kT0 + 25, EncodePointCloud2(c, kCdr));  // #1: empty
  std::string error;
  EXPECT_TRUE(w->Close(&error));
  return w->bytes();
}

TEST(BagMessageStream, BadMessagesAreSkippedCountedAndNamed) {
  std::string error;
  auto reader = McapReader::OpenBytes(BadMessagesMcap(), "bad.mcap", {}, &error);
  ASSERT_NE(reader, nullptr) << error;
  auto stream = BagMessageStream::Create(std::move(reader), {}, &error);
  ASSERT_NE(stream, nullptr) << error;
  std::vector<std::pair<TopicRole, uint64_t>> delivered;
  StreamMessage m;
  while (stream->Next(&m)) {
    delivered.emplace_back(m.role, m.index);
    if (m.cloud != nullptr) {
      EXPECT_EQ(m.cloud->scan.points.size(), 1u);
      EXPECT_EQ(m.cloud->non_finite_points, 1u);
    }
  }
  const std::vector<std::pair<TopicRole, uint64_t>> expected = {
      {TopicRole::kLidar, 0}, {TopicRole::kImu, 0}, {TopicRole::kImu, 1}, {TopicRole::kImu, 6}};
  EXPECT_EQ(delivered, expected);
  const TopicStreamStats& imu = stream->topic_stats(*stream->selected().imu);
  EXPECT_EQ(imu.delivered, 3u);
  EXPECT_EQ(imu.out_of_order, 1u);
  EXPECT_EQ(imu.duplicates, 1u);
  EXPECT_EQ(imu.bad_stamps, 1u);
  EXPECT_EQ(imu.decode_errors, 1u);
  const TopicStreamStats& pts = stream->topic_stats(*stream->selected().lidar);
  EXPECT_EQ(pts.empty, 1u);
  EXPECT_EQ(pts.non_finite_points, 1u);
  ASSERT_EQ(stream->warnings().size(), 5u);
  EXPECT_NE(stream->warnings()[1].find("bad.mcap: /imu #2: header.stamp 5 ns before"),
            std::string::npos)
      << stream->warnings()[1];
  EXPECT_NE(stream->warnings()[4].find("/imu #5: does not decode as sensor_msgs/msg/Imu"),
            std::string::npos)
      << stream->warnings()[4];
}

}  // namespace
}  // namespace swlio::drivers::bag

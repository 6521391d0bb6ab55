// The ROS 1 bag reader on bags written by the test writer (none, bz2 and lz4 chunks, closed
// and unclosed), on a bag laid out byte by byte here, and on damaged bags: cut at every
// offset, a damaged chunk, an unknown compression or op, another format version.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "bag_test_util.h"
#include "ros1_bag_writer.h"
#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "swlio/drivers/bag/ros1_bag_reader.h"

namespace swlio::drivers::bag {
namespace {

using Bytes = std::vector<uint8_t>;

struct Expected {
  std::string topic;
  int64_t t_ns;
  Bytes data;
};

/// /imu (two publishers: connections 0 and 2) and /rslidar_packets (connection 1), written
/// with times going back and forth between chunks.
Bytes WriteSample(const std::string& compression, bool closed, std::vector<Expected>* expected) {
  test::Ros1BagWriter w(compression, 600);
  w.AddConnection({0, "/imu", "sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2", "Header h"});
  w.AddConnection(
      {1, "/rslidar_packets", "rslidar_msg/RslidarPacket", "4b1cc155a9097c0cb935a7abf46d6eef", ""});
  w.AddConnection({2, "/imu", "sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2", "Header h"});
  for (int i = 0; i < 40; ++i) {
    const uint32_t conn = static_cast<uint32_t>(i % 3);
    const int64_t t = 1'600'000'000'000'000'000 + 1'000'000LL * ((i * 7) % 40);
    Bytes data(10 + static_cast<size_t>(i), static_cast<uint8_t>(i));
    w.Write(conn, t, data);
    expected->push_back({conn == 1 ? "/rslidar_packets" : "/imu", t, data});
  }
  std::stable_sort(expected->begin(), expected->end(),
                   [](const Expected& a, const Expected& b) { return a.t_ns < b.t_ns; });
  return w.Finish(closed);
}

std::unique_ptr<Ros1BagReader> OpenBytes(const Bytes& b, std::string* error) {
  return Ros1BagReader::OpenBytes(b, "test.bag", {}, error);
}

struct Variant {
  const char* compression;
  bool closed;
};

class Ros1RoundTrip : public ::testing::TestWithParam<Variant> {};

TEST_P(Ros1RoundTrip, ReadsEveryMessageInTimeOrderAndMergesPublishers) {
  std::vector<Expected> expected;
  const Bytes file = WriteSample(GetParam().compression, GetParam().closed, &expected);
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_TRUE(r->warnings().empty()) << r->warnings().front();
  ASSERT_EQ(r->topics().size(), 2u);  // two /imu connections, one topic
  const BagTopic& imu = r->topics()[0];
  EXPECT_EQ(imu.name, "/imu");
  EXPECT_EQ(imu.type, "sensor_msgs/Imu");
  EXPECT_EQ(imu.encoding, MessageEncoding::kRos1);
  EXPECT_EQ(imu.md5sum, "6a62c6daae103f4ff57a132d6f95cec2");
  EXPECT_EQ(imu.message_count, 27u);
  EXPECT_EQ(r->topics()[1].message_count, 13u);
  EXPECT_EQ(ClassifyTopic(r->topics()[1]), RosMessageKind::kRslidarPacket);  // by md5sum
  const auto all = test::ReadAll(*r);
  ASSERT_EQ(all.size(), expected.size());
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(r->topics()[all[i].topic].name, expected[i].topic) << i;
    EXPECT_EQ(all[i].log_time_ns, expected[i].t_ns) << i;
    EXPECT_EQ(all[i].data, expected[i].data) << i;
  }
  EXPECT_NE(r->StorageDescription().find(GetParam().compression), std::string::npos);
  EXPECT_EQ(r->StorageDescription().find("not closed") == std::string::npos, GetParam().closed);
}

INSTANTIATE_TEST_SUITE_P(Variants,
                         Ros1RoundTrip,
                         ::testing::Values(Variant{"none", true},
                                           Variant{"bz2", true},
                                           Variant{"lz4", true},
                                           Variant{"lz4", false},
                                           Variant{"none", false}));

/// A bag laid out by hand from the format description: version line, one Connection record
/// (conn 5, /x, std_msgs/String) and one MessageData record (time 3 s + 4 ns, data "hi" as a
/// ROS 1 string), no bag header, no index (an unclosed, minimal file).
Bytes HandLaidBag() {
  const std::string v = "#ROSBAG V2.0\n";
  Bytes b(v.begin(), v.end());
  const auto u32 = [](Bytes* out, size_t x) {
    for (int i = 0; i < 4; ++i) out->push_back(static_cast<uint8_t>(x >> (8 * i)));
  };
  // A length-prefixed block of fields, each field_len u32 | name '=' value.
  const auto block = [&](const std::vector<std::pair<std::string, Bytes>>& fields) {
    Bytes f;
    for (const auto& [name, value] : fields) {
      u32(&f, name.size() + 1 + value.size());
      f.insert(f.end(), name.begin(), name.end());
      f.push_back('=');
      f.insert(f.end(), value.begin(), value.end());
    }
    u32(&b, f.size());
    b.insert(b.end(), f.begin(), f.end());
  };
  const std::string type = "std_msgs/String";
  block({{"op", {0x07}}, {"conn", {5, 0, 0, 0}}, {"topic", {'/', 'x'}}});
  block({{"topic", {'/', 'x'}}, {"type", Bytes(type.begin(), type.end())}});  // record data
  block({{"op", {0x02}}, {"conn", {5, 0, 0, 0}}, {"time", {3, 0, 0, 0, 4, 0, 0, 0}}});
  u32(&b, 6);
  for (const uint8_t x : Bytes{2, 0, 0, 0, 'h', 'i'}) b.push_back(x);
  return b;
}

TEST(Ros1BagReader, ReadsAHandLaidBag) {
  std::string error;
  auto r = OpenBytes(HandLaidBag(), &error);
  ASSERT_NE(r, nullptr) << error;
  ASSERT_EQ(r->topics().size(), 1u);
  EXPECT_EQ(r->topics()[0].type, "std_msgs/String");
  const auto all = test::ReadAll(*r);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].log_time_ns, 3'000'000'004);
  EXPECT_EQ(all[0].data, (Bytes{2, 0, 0, 0, 'h', 'i'}));
  ASSERT_EQ(r->warnings().size(), 1u);  // no bag header record: reported, read anyway
  EXPECT_NE(r->warnings()[0].find("no bag header"), std::string::npos);
}

TEST(Ros1BagReader, RefusesOtherFormatsAndVersions) {
  std::string error;
  const std::string v12 = "#ROSBAG V1.2\n";
  EXPECT_EQ(OpenBytes(Bytes(v12.begin(), v12.end()), &error), nullptr);
  EXPECT_NE(error.find("version 1.2"), std::string::npos) << error;
  EXPECT_EQ(OpenBytes({}, &error), nullptr);
  EXPECT_NE(error.find("test.bag"), std::string::npos);
  EXPECT_EQ(Ros1BagReader::Open("/nonexistent.bag", {}, &error), nullptr);
  EXPECT_NE(error.find("/nonexistent.bag"), std::string::npos);
}

TEST(Ros1BagReader, EveryCutReadsIntactMessagesOrFailsClearly) {
  std::vector<Expected> expected;
  const Bytes file = WriteSample("lz4", true, &expected);
  for (size_t n = 0; n < file.size(); ++n) {
    const Bytes cut(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(n));
    std::string error;
    auto r = OpenBytes(cut, &error);
    if (r == nullptr) {
      EXPECT_NE(error.find("test.bag"), std::string::npos) << n;
      continue;
    }
    const auto all = test::ReadAll(*r);
    EXPECT_LE(all.size(), expected.size());
    for (const auto& m : all) {
      const auto same = [&](const Expected& e) {
        return e.t_ns == m.log_time_ns && e.data == m.data && e.topic == r->topics()[m.topic].name;
      };
      ASSERT_TRUE(std::any_of(expected.begin(), expected.end(), same)) << "cut at " << n;
    }
    if (all.size() < expected.size()) {
      EXPECT_FALSE(r->warnings().empty()) << "lost messages silently, cut at " << n;
    }
  }
}

/// Offset of the first Chunk record's data (after the bag header record at 13 + 4096).
size_t FirstChunkData(const Bytes& file) {
  ros1::Record r;
  EXPECT_TRUE(ros1::ReadRecord(std::span(file).subspan(13 + 4096), &r));
  return static_cast<size_t>(r.data.data() - file.data());
}

TEST(Ros1BagReader, ADamagedChunkIsSkippedWithAWarning) {
  for (const char* compression : {"bz2", "lz4"}) {
    std::vector<Expected> expected;
    Bytes file = WriteSample(compression, true, &expected);
    file[FirstChunkData(file) + 20] ^= 0x33;
    std::string error;
    auto r = OpenBytes(file, &error);
    ASSERT_NE(r, nullptr) << error;
    EXPECT_EQ(r->stats().chunks_skipped, 1u) << compression;
    ASSERT_FALSE(r->warnings().empty());
    EXPECT_NE(r->warnings()[0].find("chunk skipped"), std::string::npos) << r->warnings()[0];
    EXPECT_LT(test::ReadAll(*r).size(), expected.size());
  }
}

TEST(Ros1BagReader, UnknownCompressionAndOpsAreSkipped) {
  std::vector<Expected> expected;
  Bytes file = WriteSample("bz2", true, &expected);
  const std::string bz2 = "compression=bz2";
  const auto at = std::search(file.begin(), file.end(), bz2.begin(), bz2.end());
  ASSERT_NE(at, file.end());
  *(at + 14) = 'X';  // "bzX"
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_NE(r->warnings()[0].find("unknown compression 'bzX'"), std::string::npos);
  // An unknown op (0x42) appended as a record of its own.
  Bytes with_unknown = HandLaidBag();
  ros1::AppendRecord({{"op", {0x42}}}, std::vector<uint8_t>{1, 2, 3}, &with_unknown);
  r = OpenBytes(with_unknown, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_EQ(r->stats().records_skipped, 1u);
  EXPECT_EQ(test::ReadAll(*r).size(), 1u);
}

TEST(Ros1BagReader, Ros1MessagesDecodeThroughTheMessageDecoder) {
  ImuMsg imu;
  imu.header = {1'600'000'000'500'000'000, "imu_link"};
  imu.linear_acceleration_mps2 = {0.1, 0.2, 9.8};
  test::Ros1BagWriter w("lz4");
  w.AddConnection({0, "/imu", "sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2", ""});
  w.Write(0, imu.header.stamp_ns + 1000, EncodeImu(imu, MessageEncoding::kRos1));
  std::string error;
  auto r = OpenBytes(w.Finish(), &error);
  ASSERT_NE(r, nullptr) << error;
  BagMessage m;
  ASSERT_TRUE(r->Next(&m));
  DecodedMessage d;
  const BagTopic& t = r->topics()[m.topic];
  ASSERT_TRUE(DecodeMessage(ClassifyTopic(t), t.encoding, m.data, &d, &error)) << error;
  EXPECT_EQ(d.imu.header.stamp_ns, imu.header.stamp_ns);
  EXPECT_EQ(d.imu.header.frame_id, "imu_link");
  EXPECT_EQ(d.imu.linear_acceleration_mps2, imu.linear_acceleration_mps2);
}

}  // namespace
}  // namespace swlio::drivers::bag

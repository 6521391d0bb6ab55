// sensor_msgs/PointCloud2: the x, y, z (intensity) layout of point_cloud.h byte for byte, and
// the message through Cyclone DDS on loopback in one process, exact in every field (also a
// foreign layout: padded rows, two rows, big-endian flag). Domains 134..135.
#include "swlio/ipc/point_cloud.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "ipc_test_util.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/publisher.h"
#include "swlio/ipc/subscriber.h"

namespace swlio::ipc {
namespace {

using test_util::LoopbackConfig;
using test_util::WaitFor;

void ExpectField(const PointField& f, const char* name, uint32_t offset) {
  EXPECT_EQ(f.name, name);
  EXPECT_EQ(f.offset, offset);
  EXPECT_EQ(f.datatype, PointFieldType::kFloat32);
  EXPECT_EQ(static_cast<int>(f.datatype), 7);  // sensor_msgs/PointField FLOAT32
  EXPECT_EQ(f.count, 1u);
}

TEST(PointCloud, XyzLayoutIsRosFloat32LittleEndian) {
  PointCloud2 cloud;
  ASSERT_TRUE(InitXyzCloud(3, /*with_intensity=*/false, &cloud));
  EXPECT_EQ(cloud.height, 1u);
  EXPECT_EQ(cloud.width, 3u);
  ASSERT_EQ(cloud.fields.size(), 3u);
  ExpectField(cloud.fields[0], "x", 0);
  ExpectField(cloud.fields[1], "y", 4);
  ExpectField(cloud.fields[2], "z", 8);
  EXPECT_FALSE(cloud.is_bigendian);
  EXPECT_TRUE(cloud.is_dense);
  EXPECT_EQ(cloud.point_step, 12u);
  EXPECT_EQ(cloud.row_step, 36u);
  ASSERT_EQ(cloud.data.size(), 36u);
  SetPoint(1, {1.0f, -2.0f, 0.5f}, 9.0f, &cloud);
  // 1.0f = 0x3f800000, -2.0f = 0xc0000000, 0.5f = 0x3f000000, least significant byte first.
  const std::vector<uint8_t> want = {0, 0, 0x80, 0x3f, 0, 0, 0, 0xc0, 0, 0, 0, 0x3f};
  EXPECT_EQ(std::vector<uint8_t>(cloud.data.begin() + 12, cloud.data.begin() + 24), want);
  EXPECT_EQ(std::vector<uint8_t>(cloud.data.begin(), cloud.data.begin() + 12),
            std::vector<uint8_t>(12, 0));
  ASSERT_TRUE(HasXyzLayout(cloud));
  EXPECT_EQ(XyzAt(cloud, 1), (std::array<float, 3>{1.0f, -2.0f, 0.5f}));
}

TEST(PointCloud, IntensityMakesPointStepSixteen) {
  PointCloud2 cloud;
  ASSERT_TRUE(InitXyzCloud(2, /*with_intensity=*/true, &cloud));
  ASSERT_EQ(cloud.fields.size(), 4u);
  ExpectField(cloud.fields[3], "intensity", 12);
  EXPECT_EQ(cloud.point_step, 16u);
  EXPECT_EQ(cloud.row_step, 32u);
  ASSERT_EQ(cloud.data.size(), 32u);
  SetPoint(1, {3.0f, 4.0f, 5.0f}, 1.0f, &cloud);
  EXPECT_EQ(std::vector<uint8_t>(cloud.data.begin() + 28, cloud.data.end()),
            (std::vector<uint8_t>{0, 0, 0x80, 0x3f}));
  EXPECT_EQ(XyzAt(cloud, 1), (std::array<float, 3>{3.0f, 4.0f, 5.0f}));
}

TEST(PointCloud, LayoutCheckRefusesWhatXyzAtCannotRead) {
  PointCloud2 good;
  ASSERT_TRUE(InitXyzCloud(4, false, &good));
  ASSERT_TRUE(HasXyzLayout(good));
  PointCloud2 c = good;
  c.is_bigendian = true;
  EXPECT_FALSE(HasXyzLayout(c));
  c = good;
  c.fields[1].datatype = PointFieldType::kFloat64;
  EXPECT_FALSE(HasXyzLayout(c));
  c = good;
  c.fields[2].offset = 4;
  EXPECT_FALSE(HasXyzLayout(c));
  c = good;
  c.data.pop_back();
  EXPECT_FALSE(HasXyzLayout(c));
  c = good;
  c.row_step = 40;  // shorter than a row of 4 points
  EXPECT_FALSE(HasXyzLayout(c));
  c.row_step = 52;  // padded rows are fine when the data holds them
  EXPECT_FALSE(HasXyzLayout(c));
  c.data.resize(52);
  EXPECT_TRUE(HasXyzLayout(c));
}

TEST(PointCloud, TooManyPointsForARowAreRefused) {
  PointCloud2 cloud;
  EXPECT_FALSE(InitXyzCloud(size_t{1} << 32, false, &cloud));
  EXPECT_EQ(cloud.width, 0u);
}

/// A cloud whose layout is not ours: two padded rows, odd datatypes, flags flipped.
PointCloud2 ForeignCloud() {
  PointCloud2 c;
  c.t_ns = -1'500'000'001;
  c.frame_id = "velodyne";
  c.height = 2;
  c.width = 3;
  c.fields = {{"rgb", 0, PointFieldType::kUint32, 1},
              {"ring", 4, PointFieldType::kUint16, 1},
              {"", 6, static_cast<PointFieldType>(200), 7}};
  c.is_bigendian = true;
  c.point_step = 13;
  c.row_step = 41;
  c.data.resize(82);
  for (size_t i = 0; i < c.data.size(); ++i) c.data[i] = static_cast<uint8_t>(i * 37 + 5);
  c.is_dense = false;
  return c;
}

void ExpectSameCloud(const PointCloud2& a, const PointCloud2& b) {
  EXPECT_EQ(a.t_ns, b.t_ns);
  EXPECT_EQ(a.frame_id, b.frame_id);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.width, b.width);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (size_t i = 0; i < a.fields.size(); ++i) {
    EXPECT_EQ(a.fields[i].name, b.fields[i].name) << i;
    EXPECT_EQ(a.fields[i].offset, b.fields[i].offset) << i;
    EXPECT_EQ(a.fields[i].datatype, b.fields[i].datatype) << i;
    EXPECT_EQ(a.fields[i].count, b.fields[i].count) << i;
  }
  EXPECT_EQ(a.is_bigendian, b.is_bigendian);
  EXPECT_EQ(a.point_step, b.point_step);
  EXPECT_EQ(a.row_step, b.row_step);
  EXPECT_TRUE(a.data == b.data) << a.data.size() << " vs " << b.data.size() << " bytes";
  EXPECT_EQ(a.is_dense, b.is_dense);
}

/// `n` points on a spiral, with intensity when asked.
PointCloud2 Spiral(size_t n, bool with_intensity) {
  PointCloud2 c;
  c.t_ns = 1'700'000'000'123'456'789;
  c.frame_id = "map";
  EXPECT_TRUE(InitXyzCloud(n, with_intensity, &c));
  for (size_t i = 0; i < n; ++i) {
    const float t = static_cast<float>(i) * 1e-3f;
    SetPoint(i, {t * std::cos(t), t * std::sin(t), -0.5f * t}, static_cast<float>(i % 256), &c);
  }
  return c;
}

TEST(PointCloud, EveryFieldCrossesDdsExactly) {
  const IpcConfig config = LoopbackConfig(134);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  EXPECT_EQ(publisher->DdsTopicName(Topic::kMap), "rt/swlio/map");
  SubscriberOptions options;
  options.topics = {false, false, false, false, true};
  options.map_history_depth = 4;
  auto subscriber = Subscriber::Create(*participant, config, options, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  ASSERT_TRUE(WaitFor([&] { return publisher->MatchedSubscriptions(Topic::kMap) > 0; }));
  const std::vector<PointCloud2> sent = {Spiral(1000, false), Spiral(10, true), ForeignCloud(),
                                         PointCloud2{}};
  for (const PointCloud2& c : sent) ASSERT_TRUE(publisher->PublishMap(c));
  std::vector<Received<PointCloud2>> got;
  WaitFor([&] {
    subscriber->Wait(10'000'000);
    for (auto& r : subscriber->TakeMaps()) got.push_back(std::move(r));
    return got.size() >= sent.size();
  });
  ASSERT_EQ(got.size(), sent.size());
  for (size_t i = 0; i < sent.size(); ++i) ExpectSameCloud(got[i].msg, sent[i]);
  EXPECT_EQ(publisher->failures(), 0u);
}

// The current sweep (sweep_topic): BEST_EFFORT, VOLATILE, so a best-effort reader gets it
// bit for bit; an empty sweep_topic creates no writer, and publishing then fails (counted).
TEST(PointCloud, SweepTopicIsBestEffortAndOffWhenUnnamed) {
  IpcConfig config = LoopbackConfig(128);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  EXPECT_TRUE(publisher->PublishesSweeps());
  EXPECT_EQ(publisher->DdsTopicName(Topic::kSweep), "rt/swlio/cloud_registered");
  SubscriberOptions options;
  options.topics.fill(false);
  options.topics[static_cast<size_t>(Topic::kSweep)] = true;
  auto subscriber = Subscriber::Create(*participant, config, options, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  ASSERT_TRUE(WaitFor([&] { return publisher->MatchedSubscriptions(Topic::kSweep) > 0; }));
  const PointCloud2 sent = Spiral(16'000, true);
  ASSERT_TRUE(publisher->PublishSweep(sent));
  std::vector<Received<PointCloud2>> got;
  WaitFor([&] {
    subscriber->Wait(10'000'000);
    for (auto& r : subscriber->TakeSweeps()) got.push_back(std::move(r));
    return !got.empty();
  });
  ASSERT_EQ(got.size(), 1u);
  ExpectSameCloud(got[0].msg, sent);

  config.sweep_topic = "";
  auto off = Publisher::Create(*participant, config, &error);
  ASSERT_NE(off, nullptr) << error;
  EXPECT_FALSE(off->PublishesSweeps());
  EXPECT_FALSE(off->PublishSweep(sent));
  EXPECT_EQ(off->failures(), 1u);
}

TEST(PointCloud, LateSubscriberGetsTheNewestMapOfTwoHundredThousandPoints) {
  // Latched (TRANSIENT_LOCAL, KEEP_LAST 1): a reader created after the publication gets the
  // newest map only; 200,000 points with intensity are 3.2 MB.
  const IpcConfig config = LoopbackConfig(135);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  ASSERT_TRUE(publisher->PublishMap(Spiral(50, false)));
  const PointCloud2 newest = Spiral(200'000, true);
  ASSERT_EQ(newest.data.size(), 3'200'000u);
  ASSERT_TRUE(publisher->PublishMap(newest));
  SubscriberOptions options;
  options.map_history_depth = 4;  // room for more than one: only the newest may come
  auto subscriber = Subscriber::Create(*participant, config, options, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  std::vector<Received<PointCloud2>> got;
  WaitFor(
      [&] {
        subscriber->Wait(10'000'000);
        for (auto& r : subscriber->TakeMaps()) got.push_back(std::move(r));
        return !got.empty();
      },
      20.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // an older one would be here
  for (auto& r : subscriber->TakeMaps()) got.push_back(std::move(r));
  ASSERT_EQ(got.size(), 1u);
  ExpectSameCloud(got[0].msg, newest);
  EXPECT_TRUE(subscriber->TakePoses().empty());
}

}  // namespace
}  // namespace swlio::ipc

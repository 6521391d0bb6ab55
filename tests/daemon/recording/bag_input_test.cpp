// A ROS bag as the daemon's sensor input (bag_input.h): the real washing_house bag gives the
// sweeps its pcap gives; events come out in time order whatever the receive order; messages a
// run cannot use are counted; a bag without what a run needs is refused with the reason.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "../../drivers/support/bag_test_util.h"
#include "swlio/daemon/recording/bag_input.h"
#include "swlio/daemon/sensors/lidar_stage.h"
#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "swlio/drivers/bag/point_cloud_writer.h"
#include "swlio/drivers/bag/ros2msg_schema.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

namespace fs = std::filesystem;
namespace bag = drivers::bag;

std::vector<RecordingEvent> ReadAll(SensorInput& input) {
  std::vector<RecordingEvent> out;
  RecordingEvent e;
  while (input.Next(&e)) out.push_back(std::move(e));
  return out;
}

TEST(BagInput, WashingHouseBagGivesThePcapSweeps) {
  SWLIO_REQUIRE_DATA(db3, "rs16_washing_house/rosbag2_2022_08_16-11_55_30_0.db3");
  SWLIO_REQUIRE_DATA(pcap, "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap");
  const drivers::LidarConfig lidar;  // rs16
  BagInputOptions options;
  options.require_imu = false;
  std::string error;
  auto input = OpenBagInput(db3.string(), lidar, options, &error);
  ASSERT_NE(input, nullptr) << error;
  std::vector<Scan> from_bag;
  for (RecordingEvent& e : ReadAll(*input)) {
    ASSERT_EQ(e.kind, RecordingEvent::Kind::kScan);
    from_bag.push_back(std::move(e.scan));
  }
  // The same payloads through the daemon's LiDAR stage, in capture order (the stage tells
  // MSOP from DIFOP by content, as live).
  LidarStage stage(lidar);
  std::vector<Scan> from_pcap;
  HostSweep sweep;
  for (const test::Payload& p : test::PcapPayloads(pcap)) {
    stage.Add(p.bytes, p.t_ns);
    while (stage.Pop(&sweep)) from_pcap.push_back(std::move(sweep.scan));
  }
  stage.Flush();
  while (stage.Pop(&sweep)) from_pcap.push_back(std::move(sweep.scan));
  ASSERT_GE(from_pcap.size(), 30u);
  ASSERT_EQ(from_bag.size(), from_pcap.size());
  for (size_t i = 0; i < from_bag.size(); ++i) {
    bool same = from_bag[i].points.size() == from_pcap[i].points.size();
    for (size_t j = 0; same && j < from_bag[i].points.size(); ++j) {
      same = from_bag[i].points[j].xyz_m == from_pcap[i].points[j].xyz_m;
    }
    std::cerr << i << ": " << from_bag[i].points.size() << " " << from_pcap[i].points.size()
              << (same ? " same\n" : " DIFFER\n");
  }
  // Sweep 0 differs: the capture's first DIFOP (calibration) packet comes after 72 MSOP packets,
  // which are decoded with the nominal elevations, while the bag's DIFOP topic delivers its
  // first message (log time 130.2166 s) before the first scan message (130.2199 s). From sweep
  // 1 on both inputs decode with the unit's calibration.
  for (size_t i = 0; i < from_bag.size(); ++i) {
    ASSERT_EQ(from_bag[i].points.size(), from_pcap[i].points.size()) << "sweep " << i;
    for (size_t j = 0; i > 0 && j < from_bag[i].points.size(); ++j) {
      const LidarPoint& a = from_bag[i].points[j];
      const LidarPoint& b = from_pcap[i].points[j];
      // Times within the sweep come from the LiDAR's clock through each input's clock model
      // (receive times differ: capture vs bag stamps): equal to far below a firing's 2.8 µs.
      ASSERT_TRUE(a.xyz_m == b.xyz_m && a.ring == b.ring && std::abs(a.dt_ns - b.dt_ns) < 1000)
          << "sweep " << i << " point " << j << ": dt " << a.dt_ns << " vs " << b.dt_ns;
    }
  }
  EXPECT_EQ(input->stats().scans, from_bag.size());
  EXPECT_NE(input->Report().find("/rslidar_packets: 40 messages read"), std::string::npos)
      << input->Report();
}

/// An MCAP whose IMU messages arrive `imu_lag_ns` after their stamps while each cloud arrives
/// at its last point: receive order is not time order.
fs::path LaggingBag(int64_t imu_lag_ns) {
  const fs::path path = test::MakeTempDir("swlio_bag_input") / "lag.mcap";
  std::string error;
  auto w = bag::McapWriter::Create(path.string(), {}, &error);
  EXPECT_NE(w, nullptr) << error;
  const auto channel = [&](const char* topic, const char* type) {
    return w->AddChannel(w->AddSchema(type, "ros2msg", bag::Ros2MsgSchema(type)), topic, "cdr");
  };
  const uint16_t clouds = channel("/points", "sensor_msgs/msg/PointCloud2");
  const uint16_t imu = channel("/imu", "sensor_msgs/msg/Imu");
  constexpr int64_t t0 = 1'764'000'000'000'000'000;
  struct Out {
    int64_t log_ns;
    uint16_t channel;
    std::vector<uint8_t> data;
  };
  std::vector<Out> out;
  for (int i = 0; i < 400; ++i) {  // 2 s at 200 Hz
    bag::ImuMsg m;
    m.header = {t0 + i * 5'000'000LL, "imu_link"};
    m.linear_acceleration_mps2 = Eigen::Vector3d(0, 0, 9.81);
    m.angular_velocity_radps = Eigen::Vector3d(0, 0, 0.01 * i);  // a steady yaw acceleration
    out.push_back(
        {m.header.stamp_ns + imu_lag_ns, imu, bag::EncodeImu(m, bag::MessageEncoding::kCdr)});
  }
  bag::OwnedPointCloud2 cloud;
  for (int k = 0; k < 20; ++k) {  // 10 Hz sweeps of 100 points over 99 ms
    Scan s;
    s.t_start_ns = t0 + k * 100'000'000LL;
    for (int j = 0; j < 100; ++j) {
      LidarPoint p;
      p.xyz_m = Eigen::Vector3f(5.0f, 0.1f * static_cast<float>(j), 0.0f);
      p.dt_ns = j * 1'000'000LL;
      s.points.push_back(p);
    }
    bag::RslidarCloudFromScan(s, "rslidar", &cloud);
    out.push_back({s.t_start_ns + 99'000'000, clouds,
                   bag::EncodePointCloud2(cloud.msg, bag::MessageEncoding::kCdr)});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Out& a, const Out& b) { return a.log_ns < b.log_ns; });
  for (const Out& o : out) w->Write(o.channel, o.log_ns, o.log_ns, o.data);
  EXPECT_TRUE(w->Close(&error)) << error;
  return path;
}

TEST(BagInput, EventsComeInTimeOrderWhateverTheReceiveOrder) {
  std::string error;
  auto input = OpenBagInput(LaggingBag(300'000'000).string(), {}, {}, &error);
  ASSERT_NE(input, nullptr) << error;
  const std::vector<RecordingEvent> events = ReadAll(*input);
  size_t scans = 0, imu = 0;
  int64_t last_imu_ns = 0;
  int64_t last_key_ns = 0;
  for (const RecordingEvent& e : events) {
    const int64_t key = e.kind == RecordingEvent::Kind::kScan ? e.scan.t_end_ns : e.t_ns();
    EXPECT_GE(key, last_key_ns);
    last_key_ns = key;
    if (e.kind == RecordingEvent::Kind::kImu) {
      ++imu;
      last_imu_ns = e.imu.t_ns;
    } else {
      ++scans;
      // Every IMU sample up to the sweep's end came before it (the last sweep's end is the
      // bag's last IMU time, 1.995 s, minus 6 ms: covered too).
      EXPECT_GE(last_imu_ns + 5'000'000, e.scan.t_end_ns) << "sweep " << scans;
      EXPECT_EQ(e.scan.points.size(), 100u);
      // Absolute seconds in float64 hold 0.24 µs steps.
      EXPECT_NEAR(static_cast<double>(e.scan.t_end_ns - e.scan.t_start_ns), 99e6, 500.0);
    }
  }
  EXPECT_EQ(imu, 400u);
  EXPECT_EQ(scans, 20u);
}

TEST(BagInput, ReceiveTimesReplaceStampsWhenAsked) {
  std::string error;
  BagInputOptions options;
  options.stamp = BagStamp::kReceive;
  auto input = OpenBagInput(LaggingBag(2'000'000).string(), {}, options, &error);
  ASSERT_NE(input, nullptr) << error;
  for (const RecordingEvent& e : ReadAll(*input)) {
    if (e.kind != RecordingEvent::Kind::kImu) continue;
    EXPECT_EQ((e.imu.t_ns - 1'764'000'000'002'000'000) % 5'000'000, 0) << e.imu.t_ns;
  }
}

TEST(BagInput, InstantaneousImuValuesBecomeIntervalMeans) {
  const fs::path bag = LaggingBag(2'000'000);
  for (const BagImuSamples kind : {BagImuSamples::kIntervalMean, BagImuSamples::kInstantaneous}) {
    std::string error;
    BagInputOptions options;
    options.imu_samples = kind;
    auto input = OpenBagInput(bag.string(), {}, options, &error);
    ASSERT_NE(input, nullptr) << error;
    int k = 0;
    for (const RecordingEvent& e : ReadAll(*input)) {
      if (e.kind != RecordingEvent::Kind::kImu) continue;
      // Means as they are; instantaneous values averaged with the one before (the first alone).
      const double mean =
          kind == BagImuSamples::kIntervalMean || k == 0 ? 0.01 * k : 0.01 * (k - 0.5);
      EXPECT_NEAR(e.imu.gyro_radps.z(), mean, 1e-12) << k;
      EXPECT_NEAR(e.imu.acc_mps2.z(), 9.81, 1e-12) << k;
      ++k;
    }
    EXPECT_EQ(k, 400);
  }
}

TEST(BagInput, WhatARunNeedsIsNamedWhenMissing) {
  std::string error;
  BagInputOptions gnss;
  gnss.gnss = true;
  EXPECT_EQ(OpenBagInput(LaggingBag(0).string(), {}, gnss, &error), nullptr);
  EXPECT_NE(error.find("no sensor_msgs/NavSatFix topic (name one with --gnss-topic)"),
            std::string::npos)
      << error;
  BagInputOptions named;
  named.topics.imu = "/imu/data";
  EXPECT_EQ(OpenBagInput(LaggingBag(0).string(), {}, named, &error), nullptr);
  EXPECT_NE(error.find("/imu/data"), std::string::npos) << error;
  EXPECT_EQ(OpenBagInput("/nonexistent/x.mcap", {}, {}, &error), nullptr);
  EXPECT_NE(error.find("/nonexistent/x.mcap"), std::string::npos) << error;
}

TEST(BagInput, VelodynePacketsNeedTheVelodyneModel) {
  SWLIO_REQUIRE_DATA(db3, "velodyne_nebula/vlp16/1673400471837873222_0.db3");
  BagInputOptions options;
  options.require_imu = false;
  std::string error;
  EXPECT_EQ(OpenBagInput(db3.string(), {}, options, &error), nullptr);
  EXPECT_NE(error.find("lidar.model"), std::string::npos) << error;
  drivers::LidarConfig vlp16;
  vlp16.model = "vlp16";
  auto input = OpenBagInput(db3.string(), vlp16, options, &error);
  ASSERT_NE(input, nullptr) << error;
  EXPECT_GE(ReadAll(*input).size(), 2u);  // 4 scan messages of 151 packets: ~3 sweeps
}

}  // namespace
}  // namespace swlio::daemon

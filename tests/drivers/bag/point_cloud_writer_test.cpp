// A sweep written as rslidar_sdk's XYZIRT PointCloud2 (as swlio-bag export does) reads back to
// the same points, rings, intensities and times (to the double's resolution), through CDR and
// ROS 1 serialization.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "swlio/drivers/bag/point_cloud_points.h"
#include "swlio/drivers/bag/point_cloud_writer.h"

namespace swlio::drivers::bag {
namespace {

Scan TestSweep() {
  Scan s;
  s.t_start_ns = 1'764'000'000'123'456'789;  // December 2025
  for (int i = 0; i < 300; ++i) {
    LidarPoint p;
    p.xyz_m = Eigen::Vector3f(0.5f + 0.1f * static_cast<float>(i), -3.25f,
                              0.01f * static_cast<float>(i % 7));
    p.intensity = static_cast<float>(i % 256);
    p.ring = static_cast<uint16_t>(i % 16);
    p.dt_ns = static_cast<int64_t>(i) * 55'296 / 16;  // RS16 channel spacing, 3.456 µs
    s.points.push_back(p);
  }
  s.t_end_ns = s.t_start_ns + s.points.back().dt_ns;
  return s;
}

void ExpectSameSweep(const Scan& in, const Scan& out) {
  ASSERT_EQ(out.points.size(), in.points.size());
  EXPECT_NEAR(static_cast<double>(out.t_start_ns - in.t_start_ns), 0.0, 250.0);
  for (size_t i = 0; i < in.points.size(); ++i) {
    const LidarPoint& a = in.points[i];
    const LidarPoint& b = out.points[i];
    EXPECT_EQ(a.xyz_m, b.xyz_m) << i;
    EXPECT_EQ(a.intensity, b.intensity) << i;
    EXPECT_EQ(a.ring, b.ring) << i;
    // Absolute seconds as a double: within 250 ns (2⁻²² s steps near 1.76·10⁹ s).
    EXPECT_NEAR(static_cast<double>((out.t_start_ns + b.dt_ns) - (in.t_start_ns + a.dt_ns)), 0.0,
                250.0)
        << i;
  }
}

TEST(PointCloudWriter, RslidarCloudReadsBackThroughBothEncodings) {
  const Scan sweep = TestSweep();
  OwnedPointCloud2 cloud;
  RslidarCloudFromScan(sweep, "rslidar", &cloud);
  EXPECT_EQ(cloud.msg.point_step, 26u);
  EXPECT_EQ(cloud.msg.header.stamp_ns, sweep.t_start_ns);  // ts_first_point
  for (const MessageEncoding e : {MessageEncoding::kCdr, MessageEncoding::kRos1}) {
    const std::vector<uint8_t> bytes = EncodePointCloud2(cloud.msg, e);
    DecodedMessage d;
    std::string error;
    ASSERT_TRUE(DecodeMessage(RosMessageKind::kPointCloud2, e, bytes, &d, &error)) << error;
    EXPECT_EQ(d.cloud.header.frame_id, "rslidar");
    CloudPoints points;
    ASSERT_TRUE(CloudFromPointCloud2(d.cloud, {}, &points, &error)) << error;
    EXPECT_EQ(points.time_convention, PointTimeConvention::kAbsoluteSeconds);
    EXPECT_TRUE(points.has_ring);
    ExpectSameSweep(sweep, points.scan);
  }
}

TEST(PointCloudWriter, StorageIsReusedForTheNextSweep) {
  OwnedPointCloud2 cloud;
  Scan big = TestSweep(), small = TestSweep();
  small.points.resize(10);
  RslidarCloudFromScan(big, "rslidar", &cloud);
  RslidarCloudFromScan(small, "lidar_front", &cloud);
  EXPECT_EQ(cloud.msg.width, 10u);
  EXPECT_EQ(cloud.msg.data.size(), 260u);
  EXPECT_EQ(cloud.msg.header.frame_id, "lidar_front");
}

}  // namespace
}  // namespace swlio::drivers::bag

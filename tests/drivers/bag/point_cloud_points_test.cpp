// PointCloud2 → points with per-point times, for each driver's convention (research/bags.md §6),
// the override, big-endian data, NaN points, and inconsistent layouts.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "swlio/drivers/bag/point_cloud_points.h"

namespace swlio::drivers::bag {
namespace {

using Bytes = std::vector<uint8_t>;
constexpr int64_t kStamp = 1'700'000'000'000'000'000;

template <typename T>
void Put(Bytes& b, size_t at, T v) {
  const auto u =
      std::bit_cast<std::conditional_t<sizeof(T) == 8, uint64_t,
                                       std::conditional_t<sizeof(T) == 4, uint32_t, uint16_t>>>(v);
  for (size_t i = 0; i < sizeof(T); ++i) b[at + i] = static_cast<uint8_t>(u >> (8 * i));
}

/// rslidar_sdk XYZIRT: x y z intensity f32 at 0/4/8/12, ring u16 at 16, timestamp f64 at 18
/// (unaligned), point_step 26.
PointCloud2Msg RslidarCloud(const std::vector<std::array<double, 5>>& pts, Bytes* data) {
  PointCloud2Msg c;
  c.header = {kStamp, "rslidar"};
  c.height = 1;
  c.width = static_cast<uint32_t>(pts.size());
  c.fields = {{"x", 0, 7, 1},          {"y", 4, 7, 1},     {"z", 8, 7, 1},
              {"intensity", 12, 7, 1}, {"ring", 16, 4, 1}, {"timestamp", 18, 8, 1}};
  c.point_step = 26;
  c.row_step = 26 * c.width;
  data->assign(c.row_step, 0);
  for (size_t i = 0; i < pts.size(); ++i) {
    const size_t at = 26 * i;
    Put(*data, at, static_cast<float>(pts[i][0]));
    Put(*data, at + 4, static_cast<float>(pts[i][1]));
    Put(*data, at + 8, static_cast<float>(pts[i][2]));
    Put(*data, at + 12, 17.0f);
    Put(*data, at + 16, static_cast<uint16_t>(pts[i][3]));
    Put(*data, at + 18, pts[i][4]);
  }
  c.data = *data;
  return c;
}

TEST(PointCloudPoints, RslidarAbsoluteSecondsAndNanPoints) {
  Bytes data;
  const double t0 = 1'700'000'000.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto c =
      RslidarCloud({{1, 2, 3, 5, t0 + 0.001}, {nan, 0, 0, 1, t0}, {4, 5, 6, 15, t0}}, &data);
  CloudPoints out;
  std::string error;
  ASSERT_TRUE(CloudFromPointCloud2(c, {}, &out, &error)) << error;
  EXPECT_EQ(out.time_convention, PointTimeConvention::kAbsoluteSeconds);
  EXPECT_TRUE(out.has_ring);
  EXPECT_EQ(out.points_in, 3u);
  EXPECT_EQ(out.non_finite_points, 1u);
  ASSERT_EQ(out.scan.points.size(), 2u);
  EXPECT_EQ(out.scan.t_start_ns, 1'700'000'000'000'000'000);
  // float64 seconds near 1.7e9 resolve ~0.24 µs: the 1 ms offset comes back within that.
  EXPECT_NEAR(static_cast<double>(out.scan.points[0].dt_ns), 1e6, 300);
  EXPECT_EQ(out.scan.points[1].dt_ns, 0);
  EXPECT_NEAR(static_cast<double>(out.scan.t_end_ns - out.scan.t_start_ns), 1e6, 300);
  EXPECT_EQ(out.scan.points[0].ring, 5);
  EXPECT_EQ(out.scan.points[1].ring, 15);
  EXPECT_EQ(out.scan.points[0].xyz_m, Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(out.scan.points[0].intensity, 17.0f);
}

/// velodyne_pointcloud: x y z intensity f32, ring u16 at 16, time f32 at 18, point_step 22.
TEST(PointCloudPoints, VelodyneRelativeSecondsMayBeNegative) {
  PointCloud2Msg c;
  c.header = {kStamp, "velodyne"};
  c.height = 1;
  c.width = 2;
  c.fields = {{"x", 0, 7, 1},          {"y", 4, 7, 1},     {"z", 8, 7, 1},
              {"intensity", 12, 7, 1}, {"ring", 16, 4, 1}, {"time", 18, 7, 1}};
  c.point_step = 22;
  c.row_step = 44;
  Bytes data(44, 0);
  Put(data, 0, 1.0f);
  Put(data, 18, -0.1f);  // the header carries the last packet's time
  Put(data, 22, 2.0f);
  Put(data, 22 + 18, 0.0f);
  c.data = data;
  CloudPoints out;
  std::string error;
  ASSERT_TRUE(CloudFromPointCloud2(c, {}, &out, &error)) << error;
  EXPECT_EQ(out.time_convention, PointTimeConvention::kRelativeSeconds);
  ASSERT_EQ(out.scan.points.size(), 2u);
  EXPECT_NEAR(static_cast<double>(out.scan.t_start_ns - kStamp), -1e8, 10);
  EXPECT_EQ(out.scan.t_end_ns, kStamp);
  EXPECT_EQ(out.scan.points[0].dt_ns, 0);
  EXPECT_NEAR(static_cast<double>(out.scan.points[1].dt_ns), 1e8, 10);
}

/// ouster-ros default point: x y z (+pad) f32 at 0/4/8, intensity f32 16, t u32 20,
/// reflectivity u16 24, ring u16 26, ambient u16 28, range u32 32; point_step 48.
TEST(PointCloudPoints, OusterRelativeNanosecondsInAPaddedLayout) {
  PointCloud2Msg c;
  c.header = {kStamp, "os_lidar"};
  c.height = 2;  // organized: 2 rows of 1
  c.width = 1;
  c.fields = {{"x", 0, 7, 1},  {"y", 4, 7, 1},     {"z", 8, 7, 1},     {"intensity", 16, 7, 1},
              {"t", 20, 6, 1}, {"ring", 26, 4, 1}, {"range", 32, 6, 1}};
  c.point_step = 48;
  c.row_step = 48;
  Bytes data(96, 0);
  Put(data, 0, 3.0f);
  Put(data, 20, uint32_t{50'000});
  Put(data, 26, uint16_t{63});
  Put(data, 48, 4.0f);
  Put(data, 48 + 20, uint32_t{0});
  c.data = data;
  CloudPoints out;
  std::string error;
  ASSERT_TRUE(CloudFromPointCloud2(c, {}, &out, &error)) << error;
  EXPECT_EQ(out.time_convention, PointTimeConvention::kRelativeNanoseconds);
  ASSERT_EQ(out.scan.points.size(), 2u);
  EXPECT_EQ(out.scan.t_start_ns, kStamp);
  EXPECT_EQ(out.scan.points[0].dt_ns, 50'000);
  EXPECT_EQ(out.scan.points[0].ring, 63);
}

TEST(PointCloudPoints, NoTimeFieldAndTheOverride) {
  Bytes data;
  auto c = RslidarCloud({{1, 0, 0, 0, 0.25}, {2, 0, 0, 0, 0.5}}, &data);
  c.fields[5].name = "stamp_s";  // an unusual name: not detected
  CloudPoints out;
  std::string error;
  ASSERT_TRUE(CloudFromPointCloud2(c, {}, &out, &error)) << error;
  EXPECT_EQ(out.time_convention, PointTimeConvention::kNone);
  EXPECT_EQ(out.scan.t_start_ns, kStamp);
  EXPECT_EQ(out.scan.points[1].dt_ns, 0);
  CloudOptions o;
  o.time = PointTimeConvention::kRelativeSeconds;
  o.time_field = "stamp_s";
  ASSERT_TRUE(CloudFromPointCloud2(c, o, &out, &error)) << error;
  EXPECT_EQ(out.scan.t_start_ns, kStamp + 250'000'000);
  EXPECT_EQ(out.scan.points[1].dt_ns, 250'000'000);
  o.time_field = "missing";
  EXPECT_FALSE(CloudFromPointCloud2(c, o, &out, &error));
  EXPECT_NE(error.find("missing"), std::string::npos);
  PointTimeConvention parsed;
  EXPECT_TRUE(ParsePointTimeConvention("relative_ns", &parsed));
  EXPECT_EQ(parsed, PointTimeConvention::kRelativeNanoseconds);
  EXPECT_FALSE(ParsePointTimeConvention("sometimes", &parsed));
}

TEST(PointCloudPoints, BigEndianData) {
  PointCloud2Msg c;
  c.header = {kStamp, "be"};
  c.height = 1;
  c.width = 1;
  c.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}};
  c.is_bigendian = true;
  c.point_step = 12;
  c.row_step = 12;
  Bytes data(12, 0);
  const auto be = std::bit_cast<uint32_t>(1.5f);
  for (size_t i = 0; i < 4; ++i) data[i] = static_cast<uint8_t>(be >> (24 - 8 * i));
  c.data = data;
  CloudPoints out;
  std::string error;
  ASSERT_TRUE(CloudFromPointCloud2(c, {}, &out, &error)) << error;
  EXPECT_EQ(out.scan.points[0].xyz_m.x(), 1.5f);
  EXPECT_FALSE(out.has_ring);
}

TEST(PointCloudPoints, InconsistentLayoutsAreErrors) {
  Bytes data;
  const auto good = RslidarCloud({{1, 2, 3, 0, 1.0}, {1, 2, 3, 0, 1.0}}, &data);
  CloudPoints out;
  std::string error;
  auto c = good;
  c.row_step = 30;  // < width × point_step
  EXPECT_FALSE(CloudFromPointCloud2(c, {}, &out, &error));
  c = good;
  c.height = 2;  // data holds one row
  EXPECT_FALSE(CloudFromPointCloud2(c, {}, &out, &error));
  EXPECT_NE(error.find("data holds"), std::string::npos) << error;
  c = good;
  c.fields[0].offset = 24;  // x past point_step
  EXPECT_FALSE(CloudFromPointCloud2(c, {}, &out, &error));
  c = good;
  c.fields.erase(c.fields.begin());  // no x
  EXPECT_FALSE(CloudFromPointCloud2(c, {}, &out, &error));
  c = good;
  c.fields[2].datatype = 42;  // unknown datatype
  EXPECT_FALSE(CloudFromPointCloud2(c, {}, &out, &error));
  c = good;
  c.width = 0;  // empty but consistent
  c.row_step = 0;
  ASSERT_TRUE(CloudFromPointCloud2(c, {}, &out, &error)) << error;
  EXPECT_TRUE(out.scan.points.empty());
}

}  // namespace
}  // namespace swlio::drivers::bag

// Range image projection: columns from azimuth, rejects, collisions.
#include "swlio/estimator/frontend/range_image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "synthetic_scan.h"

namespace swlio::estimator {
namespace {

using test::At;

TEST(RangeImage, ColumnIsTheAzimuthClockwiseFromX) {
  RangeImage image(RangeImageConfig{});
  EXPECT_EQ(image.Column({1.0f, 0.0f, 0.0f}), 900);    // forward (+x)
  EXPECT_EQ(image.Column({0.0f, -1.0f, 0.0f}), 1350);  // right (−y)
  EXPECT_EQ(image.Column({0.0f, 1.0f, 0.0f}), 450);    // left (+y)
  EXPECT_EQ(image.Column(At(3, 17, 10.0).xyz_m), 17);
}

// The column uses a polynomial atan2: it agrees with std::atan2's column everywhere but within
// 0.001° of a column border.
TEST(RangeImage, FastAzimuthMatchesStdAtan2) {
  RangeImage image(RangeImageConfig{});
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int n = 0; n < 200000; ++n) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const double bins =
        (std::atan2(-p.y(), p.x()) + std::numbers::pi) / (2.0 * std::numbers::pi) * 1800.0;
    if (std::abs(bins - std::round(bins)) < 0.001 / 0.2) continue;
    ASSERT_EQ(image.Column(p.cast<float>()), std::min(static_cast<int>(bins), 1799))
        << p.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 190000);
}

// In the drivers' frame (x forward, y left): column 0 just behind the sensor on its left,
// forward in the middle, and columns growing clockwise seen from above (right is 3/4).
TEST(RangeImage, ColumnZeroIsBehindTheSensorAndColumnsGrowClockwise) {
  RangeImage image(RangeImageConfig{});
  EXPECT_EQ(image.Column(Eigen::Vector3f(-5.0f, 0.001f, 0.0f)), 0);
  EXPECT_EQ(image.Column(Eigen::Vector3f(-5.0f, -0.001f, 0.0f)), 1799);
  EXPECT_EQ(image.Column(Eigen::Vector3f(5.0f, 0.001f, 1.0f)), 899);
  EXPECT_EQ(image.Column(Eigen::Vector3f(5.0f, -0.001f, 1.0f)), 900);
  EXPECT_EQ(image.Column(Eigen::Vector3f(-0.001f, -5.0f, 0.0f)), 1350);  // right: +90°
  EXPECT_EQ(image.Column(Eigen::Vector3f(-0.001f, 5.0f, 0.0f)), 449);    // left: −90°
}

TEST(RangeImage, CountsRejectsAndKeepsTheNearerOfColliding) {
  RangeImage image(RangeImageConfig{});
  std::vector<LidarPoint> points = {At(2, 100, 10.0), At(2, 100, 8.0), At(2, 100, 9.0),
                                    At(2, 100, 7.0),  At(2, 300, 0.1), At(16, 5, 5.0)};
  const RangeImageStats stats = image.Build(points);
  EXPECT_EQ(stats.placed, 3);  // column 100, then its free neighbours 101 and 99
  EXPECT_EQ(stats.collisions, 1);
  EXPECT_EQ(stats.out_of_range, 1);
  EXPECT_EQ(stats.bad_ring, 1);
  EXPECT_EQ(image.Index(image.Cell(2, 100)), 3);  // 7 m replaced 10 m
  EXPECT_EQ(image.Index(image.Cell(2, 101)), 1);
  EXPECT_EQ(image.Index(image.Cell(2, 99)), 2);
  EXPECT_NEAR(image.Range(image.Cell(2, 100)), 7.0f, 1e-4f);
  EXPECT_EQ(image.Index(image.Cell(2, 300)), RangeImage::kEmpty);
}

}  // namespace
}  // namespace swlio::estimator

// Mixed pixels at an occlusion jump (FeatureConfig::mixed_pixel_tolerance_m, off by default;
// here at 0.15 m): one ring of a synthetic segmented cloud, a wall seen obliquely and a wall far
// behind it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "swlio/estimator/frontend/feature_extractor.h"

namespace swlio::estimator {
namespace {

constexpr double kColumnRad = 0.2 * M_PI / 180.0;  // RS-LiDAR-16 at 600 rpm

// A near wall (the line x = 10 m, seen from the origin) in columns [0, edge], a far wall at
// 25 m after it; `edge_range_m` replaces the range of the near wall's last point (0: its own).
// Column 85 lies inside a sector of the default six (the last point of one would have its
// neighbour in the next chosen first).
SegmentationResult Ring(double edge_range_m, int columns = 200, int edge = 85) {
  SegmentationResult s;
  for (int c = 0; c < columns; ++c) {
    const double azimuth = (c - 50) * kColumnRad;
    double r = c <= edge ? 10.0 / std::cos(azimuth) : 25.0;
    if (c == edge && edge_range_m > 0.0) r = edge_range_m;
    SegmentedPoint p;
    p.range_m = static_cast<float>(r);
    p.xyz_m = Eigen::Vector3f(static_cast<float>(r * std::cos(azimuth)),
                              static_cast<float>(r * std::sin(azimuth)), 0.0f);
    p.column = static_cast<uint16_t>(c);
    p.source_index = static_cast<uint32_t>(c);
    p.label = 1;
    s.points.push_back(p);
  }
  s.ring_begin = {0, static_cast<uint32_t>(columns)};
  return s;
}

FeatureConfig Tested() {
  FeatureConfig config;
  config.mixed_pixel_tolerance_m = 0.15;
  return config;
}

bool Contains(const std::vector<FeaturePoint>& points, uint32_t source_index) {
  return std::any_of(points.begin(), points.end(),
                     [&](const FeaturePoint& p) { return p.source_index == source_index; });
}

FeatureSet Features(const FeatureConfig& config, const SegmentationResult& ring) {
  FeatureExtractor extractor{config};
  FeatureSet f;
  extractor.Extract(ring, &f);
  return f;
}

double NearRange(int column) { return 10.0 / std::cos((column - 50) * kColumnRad); }

TEST(MixedPixel, TheTrueEdgePointStaysAnEdge) {
  const FeatureSet f = Features(Tested(), Ring(0.0));
  EXPECT_EQ(f.mixed, 0);
  EXPECT_TRUE(Contains(f.edges, 85));
}

// The return merged from both walls (power-weighted, so nearer the near one): 0.2 m behind
// the near wall's line, within the occlusion test's 0.3 m, so that test keeps it as the edge.
TEST(MixedPixel, AReturnBetweenTheWallsIsNoFeature) {
  const FeatureSet f = Features(Tested(), Ring(NearRange(85) + 0.2));
  EXPECT_EQ(f.mixed, 1);
  EXPECT_FALSE(Contains(f.edges, 85));
  EXPECT_FALSE(Contains(f.planes, 85));
}

TEST(MixedPixel, OffKeepsItAsTheEdge) {
  const FeatureSet f = Features(FeatureConfig{}, Ring(NearRange(85) + 0.2));
  EXPECT_EQ(f.mixed, 0);
  EXPECT_TRUE(Contains(f.edges, 85));
}

// Range noise of a few centimetres on the edge point is no mixed pixel.
TEST(MixedPixel, RangeNoiseIsNoMixedPixel) {
  const FeatureSet f = Features(Tested(), Ring(NearRange(85) + 0.06));
  EXPECT_EQ(f.mixed, 0);
}

// The same from the other side: the far wall first, then the near wall.
TEST(MixedPixel, SeenFromTheFarSideToo) {
  SegmentationResult s = Ring(0.0);
  std::reverse(s.points.begin(), s.points.end());
  for (size_t i = 0; i < s.points.size(); ++i) s.points[i].column = static_cast<uint16_t>(i);
  FeatureSet f = Features(Tested(), s);
  EXPECT_EQ(f.mixed, 0);
  EXPECT_TRUE(Contains(f.edges, 85));
  // Reversed, the near wall's edge (source 85) sits at index 114.
  s.points[114].range_m += 0.2f;
  f = Features(Tested(), s);
  EXPECT_EQ(f.mixed, 1);
  EXPECT_FALSE(Contains(f.edges, 85));
}

}  // namespace
}  // namespace swlio::estimator

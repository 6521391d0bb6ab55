// The keyframe store (issue 33): clouds kept in float only where asked, their bytes counted,
// and points handed back moved and within f32 rounding of what went in.
#include "swlio/estimator/loop/keyframe_store.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace swlio::estimator {
namespace {

KeyframeCloud Cloud(size_t planes, size_t edges) {
  KeyframeCloud kf;
  for (size_t i = 0; i < planes; ++i)
    kf.planes_lidar.emplace_back(0.1 * static_cast<double>(i) + 1e-9, 100.0 + 1.0 / 3.0, -2.0);
  for (size_t i = 0; i < edges; ++i)
    kf.edges_lidar.emplace_back(5.0, -0.2, 0.01 * static_cast<double>(i));
  return kf;
}

TEST(KeyframeStore, KeepsCloudsOnlyWhereAskedAndCountsTheirBytes) {
  KeyframeStore store;
  store.Add(Cloud(100, 20), true);
  store.Add(Cloud(50, 5), false);
  store.Add(Cloud(10, 0), true);
  EXPECT_EQ(store.size(), 3u);
  EXPECT_EQ(store.clouds(), 2u);
  EXPECT_TRUE(store.has_cloud(0));
  EXPECT_FALSE(store.has_cloud(1));
  // Each point and its visibility score (visibility_image.h).
  EXPECT_EQ(store.bytes(), (120u + 10u) * (3u * sizeof(float) + sizeof(int8_t)));
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_TRUE(store.Planes(1, I).empty());
  EXPECT_TRUE(store.Edges(1, I).empty());
  EXPECT_EQ(store.Planes(2, I).size(), 10u);
}

TEST(KeyframeStore, HandsBackPointsMovedWithinFloatRounding) {
  KeyframeStore store;
  const KeyframeCloud kf = Cloud(30, 4);
  store.Add(kf, true);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Eigen::Vector3d(10.0, -3.0, 0.5));
  T.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  const std::vector<Eigen::Vector3d> planes = store.Planes(0, T);
  const std::vector<Eigen::Vector3d> edges = store.Edges(0, T);
  ASSERT_EQ(planes.size(), 30u);
  ASSERT_EQ(edges.size(), 4u);
  double worst_m = 0.0;
  for (size_t i = 0; i < planes.size(); ++i)
    worst_m = std::max(worst_m, (planes[i] - T * kf.planes_lidar[i]).norm());
  for (size_t i = 0; i < edges.size(); ++i)
    worst_m = std::max(worst_m, (edges[i] - T * kf.edges_lidar[i]).norm());
  // f32 below 128 m: ≤ 3.8 µm per coordinate (saved_map.h).
  EXPECT_LT(worst_m, 1e-5);
  EXPECT_GT(worst_m, 0.0);  // really float: 100 + 1/3 is not exact in f32
  // The saved map's f32 of the stored point is the f32 of the original.
  EXPECT_EQ(store.Planes(0, Eigen::Isometry3d::Identity())[3].cast<float>(),
            kf.planes_lidar[3].cast<float>());
}

}  // namespace
}  // namespace swlio::estimator

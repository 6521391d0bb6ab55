#include "swlio/estimator/registration/voxel_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace swlio::estimator {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(size_t n, double extent, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  std::vector<Eigen::Vector3d> pts(n);
  for (auto& p : pts) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return pts;
}

TEST(VoxelMap, NearestMatchesBruteForce) {
  VoxelMapConfig config;
  config.voxel_m = 1.0;
  config.max_points_per_voxel = 1000;
  config.min_point_spacing_m = 0.0;
  VoxelMap map(config);
  const auto pts = RandomPoints(5000, 5.0, 1);
  ASSERT_EQ(map.Insert(pts), pts.size());
  std::vector<Eigen::Vector3d> got;
  for (const auto& q : RandomPoints(200, 4.0, 2)) {
    map.Nearest(q, 5, 1.0, &got);
    std::vector<double> d;
    for (const auto& p : pts) {
      if ((p - q).norm() <= 1.0) d.push_back((p - q).norm());
    }
    std::sort(d.begin(), d.end());
    ASSERT_EQ(got.size(), std::min<size_t>(5, d.size()));
    for (size_t i = 0; i < got.size(); ++i) EXPECT_DOUBLE_EQ((got[i] - q).norm(), d[i]);
  }
}

TEST(VoxelMap, BoundsPointsPerVoxelSpacingAndRadius) {
  VoxelMapConfig config;
  config.voxel_m = 1.0;
  config.max_points_per_voxel = 4;
  config.min_point_spacing_m = 0.05;
  config.radius_m = 10.0;
  VoxelMap map(config);
  std::vector<Eigen::Vector3d> same(10, Eigen::Vector3d(0.5, 0.5, 0.5));
  EXPECT_EQ(map.Insert(same), 1u);            // duplicates are spaced out
  auto inside = RandomPoints(1000, 0.49, 3);  // all in the voxel [0, 1)³
  for (auto& p : inside) p += Eigen::Vector3d::Constant(0.5);
  EXPECT_EQ(map.Insert(inside), 3u);  // one voxel holds at most 4
  map.Insert({Eigen::Vector3d(50.5, 0.5, 0.5)});
  EXPECT_EQ(map.voxels(), 2u);
  EXPECT_EQ(map.RemoveFar(Eigen::Vector3d::Zero()), 1u);
  EXPECT_EQ(map.size(), 4u);
}

}  // namespace
}  // namespace swlio::estimator

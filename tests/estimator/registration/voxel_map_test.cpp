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

// The registration's case (lidar_odometry.h: 0.5 m cells, ≤ 10 points 0.1 m apart; k = 6 within
// 1.5 m): points on surfaces. Most of the 26 cells around the query's own are never searched;
// queries near cell faces, edges and corners, and off the surfaces (own cell empty), need some.
// Against brute force over every stored point.
TEST(VoxelMap, NearestMatchesBruteForceOnSurfaces) {
  VoxelMap map({.voxel_m = 0.5, .max_points_per_voxel = 10});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  std::vector<Eigen::Vector3d> surface;
  for (int i = 0; i < 20000; ++i) {
    const double a = u(rng);
    const double b = u(rng);
    surface.emplace_back(a, b, 0.05 * a);         // a sloped floor
    surface.emplace_back(1.3, a, 2.0 + 0.5 * b);  // a wall
  }
  map.Insert(surface);
  const std::vector<Eigen::Vector3d> stored = map.Points();
  ASSERT_GT(stored.size(), 1000u);
  std::vector<Eigen::Vector3d> got;
  size_t from_other_cells = 0;
  for (const Eigen::Vector3d& q : RandomPoints(2000, 4.5, 8)) {
    const Eigen::Vector3d query(q.x(), q.y(), 0.06 * q.z() + 0.05 * q.x());  // near the floor
    map.Nearest(query, 6, 1.5, &got);
    std::vector<std::pair<double, Eigen::Vector3d>> d;
    for (const Eigen::Vector3d& p : stored) {
      if ((p - query).norm() < 1.5) d.emplace_back((p - query).squaredNorm(), p);
    }
    std::sort(d.begin(), d.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    ASSERT_EQ(got.size(), std::min<size_t>(6, d.size()));
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ((got[i] - query).squaredNorm(), d[i].first);
      from_other_cells += map.SameVoxel(got[i], query) ? 0 : 1;
    }
  }
  EXPECT_GT(from_other_cells, 1000u);  // the neighbouring cells were needed, and searched
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

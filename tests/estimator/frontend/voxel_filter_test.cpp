// Voxel filter of paper eqs. (14)–(16) and its fixed-cell variant.
#include "swlio/estimator/frontend/voxel_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "swlio/estimator/frontend/feature_extractor.h"

namespace swlio::estimator {
namespace {

using Cell = std::array<int64_t, 3>;

std::vector<Eigen::Vector3f> UniformCloud(size_t n, const Eigen::Vector3f& size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Eigen::Vector3f> points(n);
  for (auto& p : points) p = Eigen::Vector3f(u(rng), u(rng), u(rng)).cwiseProduct(size);
  return points;
}

/// Independent reference: the voxels of eq. (16) with their members.
std::map<Cell, std::vector<uint32_t>> Voxels(const std::vector<Eigen::Vector3f>& points,
                                             const Eigen::Vector3f& origin,
                                             double cell) {
  std::map<Cell, std::vector<uint32_t>> voxels;
  for (uint32_t i = 0; i < points.size(); ++i) {
    Cell c;
    for (int a = 0; a < 3; ++a) {
      c[static_cast<size_t>(a)] =
          static_cast<int64_t>(std::floor(static_cast<double>(points[i][a] - origin[a]) / cell));
    }
    voxels[c].push_back(i);
  }
  return voxels;
}

/// Every voxel is represented exactly once, by one of its points nearest its centroid.
void ExpectRepresentatives(const std::vector<Eigen::Vector3f>& points,
                           const Eigen::Vector3f& origin,
                           double cell,
                           const std::vector<uint32_t>& kept) {
  const auto voxels = Voxels(points, origin, cell);
  ASSERT_EQ(kept.size(), voxels.size());
  std::map<uint32_t, Cell> voxel_of;
  for (const auto& [c, members] : voxels) {
    for (uint32_t i : members) voxel_of[i] = c;
  }
  std::map<Cell, int> seen;
  for (uint32_t k : kept) {
    const auto& members = voxels.at(voxel_of.at(k));
    ++seen[voxel_of.at(k)];
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (uint32_t i : members) centroid += points[i].cast<double>();
    centroid /= static_cast<double>(members.size());
    const double dk = (points[k].cast<double>() - centroid).norm();
    for (uint32_t i : members) EXPECT_LE(dk, (points[i].cast<double>() - centroid).norm() + 1e-5);
  }
  for (const auto& [c, count] : seen) EXPECT_EQ(count, 1);
}

TEST(AdaptiveCellSize, FollowsEquation14) {
  // ∛(8 · 10·20·5 / 1000) = ∛8 = 2.
  EXPECT_NEAR(AdaptiveCellSize({10.0f, 20.0f, 5.0f}, 1000, 8.0, 0.05), 2.0, 1e-9);
  // A flat cloud: l_z raised to the minimum extent, ∛(5 · 30·40·0.1 / 600) = 1.
  EXPECT_NEAR(AdaptiveCellSize({30.0f, 40.0f, 0.0f}, 600, 5.0, 0.1), 1.0, 1e-6);
}

TEST(VoxelFilter, LatticeKeepsTheCentrePointOfEachVoxel) {
  // 10×10×10 points at 0.05 + 0.1·i in a unit cube; 0.5 m cells from the origin hold 5×5×5
  // points each, whose centroid (0.25 + 0.5·j per axis) is itself a lattice point.
  std::vector<Eigen::Vector3f> points;
  for (int x = 0; x < 10; ++x) {
    for (int y = 0; y < 10; ++y) {
      for (int z = 0; z < 10; ++z)
        points.push_back(
            Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)) *
                0.1f +
            Eigen::Vector3f::Constant(0.05f));
    }
  }
  VoxelFilter filter;
  std::vector<uint32_t> kept;
  const VoxelFilterResult r = filter.FilterFixed(points, 0.5, &kept);
  EXPECT_EQ(r.voxels, 8u);
  ASSERT_EQ(kept.size(), 8u);
  for (uint32_t k : kept) {
    for (int a = 0; a < 3; ++a) {
      const float v = points[k][a];
      EXPECT_TRUE(std::abs(v - 0.25f) < 1e-5f || std::abs(v - 0.75f) < 1e-5f) << v;
    }
  }
}

TEST(VoxelFilter, FixedCellRepresentativesAreNearestToCentroids) {
  const auto points = UniformCloud(5000, {6.0f, 4.0f, 2.0f}, 7);
  VoxelFilter filter;
  std::vector<uint32_t> kept;
  filter.FilterFixed(points, 0.7, &kept);
  ExpectRepresentatives(points, Eigen::Vector3f::Zero(), 0.7, kept);
}

TEST(VoxelFilter, AdaptiveCellGivesAboutKPointsPerVoxel) {
  const auto points = UniformCloud(20000, {20.0f, 10.0f, 4.0f}, 11);
  Eigen::Vector3f lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3f l = hi - lo;
  const double expected_cell = std::cbrt(8.0 * l.x() * l.y() * l.z() / 20000.0);  // eq. (14)
  VoxelFilterConfig config;
  config.points_per_voxel = 8.0;
  VoxelFilter filter;
  std::vector<uint32_t> kept;
  const VoxelFilterResult r = filter.FilterAdaptive(points, config, &kept);
  EXPECT_NEAR(r.cell_m, expected_cell, 1e-4);
  for (int a = 0; a < 3; ++a) {  // eq. (15)
    EXPECT_EQ(r.grid[a], static_cast<int>(std::floor(l[a] / r.cell_m)));
  }
  EXPECT_LE(r.voxels, static_cast<size_t>((r.grid.x() + 1) * (r.grid.y() + 1) * (r.grid.z() + 1)));
  const double per_voxel = 20000.0 / static_cast<double>(r.voxels);
  EXPECT_GT(per_voxel, 0.5 * config.points_per_voxel);
  EXPECT_LT(per_voxel, 1.5 * config.points_per_voxel);
  ExpectRepresentatives(points, lo, r.cell_m, kept);
}

TEST(VoxelFilter, AdaptiveCellIsClamped) {
  const auto points = UniformCloud(10, {100.0f, 100.0f, 10.0f}, 3);
  VoxelFilterConfig config;
  VoxelFilter filter;
  std::vector<uint32_t> kept;
  EXPECT_DOUBLE_EQ(filter.FilterAdaptive(points, config, &kept).cell_m, config.max_cell_m);
  EXPECT_EQ(filter.FilterAdaptive({}, config, &kept).voxels, 0u);
  EXPECT_TRUE(kept.empty());
}

TEST(VoxelFilter, DeterministicAndIndependentOfInputOrder) {
  const auto points = UniformCloud(8000, {10.0f, 10.0f, 3.0f}, 5);
  std::vector<Eigen::Vector3f> shuffled = points;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(99));
  VoxelFilter filter;
  std::vector<uint32_t> a, b, c;
  filter.FilterFixed(points, 0.5, &a);
  filter.FilterFixed(points, 0.5, &b);
  EXPECT_EQ(a, b);
  filter.FilterFixed(shuffled, 0.5, &c);
  ASSERT_EQ(a.size(), c.size());
  auto less = [](const Eigen::Vector3f& p, const Eigen::Vector3f& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  };
  std::vector<Eigen::Vector3f> pa, pc;
  for (uint32_t i : a) pa.push_back(points[i]);
  for (uint32_t i : c) pc.push_back(shuffled[i]);
  std::sort(pa.begin(), pa.end(), less);
  std::sort(pc.begin(), pc.end(), less);
  EXPECT_EQ(pa, pc);
}

TEST(VoxelFilter, ApplyCompactsFeaturePointsInInputOrder) {
  const auto positions = UniformCloud(3000, {5.0f, 5.0f, 1.0f}, 13);
  std::vector<FeaturePoint> features;
  for (uint32_t i = 0; i < positions.size(); ++i) features.push_back({positions[i], i, 0.0f, i, 0});
  VoxelFilter filter;
  std::vector<uint32_t> kept;
  filter.FilterFixed(positions, 0.4, &kept);
  std::sort(kept.begin(), kept.end());
  const VoxelFilterResult r = filter.Apply(&features, 0.4);
  ASSERT_EQ(features.size(), r.voxels);
  ASSERT_EQ(features.size(), kept.size());
  for (size_t i = 0; i < kept.size(); ++i) {
    EXPECT_EQ(features[i].source_index, kept[i]);
    EXPECT_EQ(features[i].xyz_m, positions[kept[i]]);
  }
}

}  // namespace
}  // namespace swlio::estimator

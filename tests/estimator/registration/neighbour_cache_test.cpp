#include "swlio/estimator/registration/neighbour_cache.h"

#include <gtest/gtest.h>

#include <random>

#include "swlio/core/lie.h"
#include "swlio/estimator/registration/scan_matcher.h"

namespace swlio::estimator {
namespace {

/// Random points on three walls and the ground, and on two poles: no two map points at the
/// same distance from a query by construction (a regular grid would tie, and ties are never
/// reused).
struct Cloud {
  std::vector<Eigen::Vector3d> planes;
  std::vector<Eigen::Vector3d> edges;
};

Cloud RandomYard(size_t n, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-8.0, 8.0), h(0.0, 3.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  Cloud c;
  for (size_t i = 0; i < n; ++i) {
    c.planes.emplace_back(u(*rng), u(*rng), noise(*rng));
    c.planes.emplace_back(9.0 + noise(*rng), u(*rng), h(*rng));
    c.planes.emplace_back(u(*rng), -9.0 + noise(*rng), h(*rng));
    c.edges.emplace_back(2.0 + noise(*rng), 3.0 + noise(*rng), h(*rng));
    c.edges.emplace_back(-4.0 + noise(*rng), 1.0 + noise(*rng), h(*rng));
  }
  return c;
}

Eigen::Isometry3d Step(std::mt19937* rng, double translation_m, double rotation_rad) {
  std::normal_distribution<double> t(0.0, translation_m), r(0.0, rotation_rad);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::Exp(Eigen::Vector3d(r(*rng), r(*rng), r(*rng)));
  T.translation() = Eigen::Vector3d(t(*rng), t(*rng), t(*rng));
  return T;
}

struct Associations {
  std::vector<PlaneCorrespondence> planes;
  std::vector<LineCorrespondence> lines;
};

Associations Associate(const ScanMatcher& matcher,
                       const Cloud& scan,
                       const VoxelMap& plane_map,
                       const VoxelMap& edge_map,
                       const Eigen::Isometry3d& T,
                       NeighbourCache* cache) {
  Associations a;
  matcher.Associate(scan.planes, scan.edges, plane_map, edge_map, T, &a.planes, &a.lines, cache);
  return a;
}

/// Bit for bit: the cache must not change a single correspondence.
void ExpectSame(const Associations& got, const Associations& want) {
  ASSERT_EQ(got.planes.size(), want.planes.size());
  for (size_t i = 0; i < got.planes.size(); ++i) {
    EXPECT_EQ(got.planes[i].index, want.planes[i].index);
    EXPECT_EQ(got.planes[i].normal, want.planes[i].normal);
    EXPECT_EQ(got.planes[i].centroid, want.planes[i].centroid);
  }
  ASSERT_EQ(got.lines.size(), want.lines.size());
  for (size_t i = 0; i < got.lines.size(); ++i) {
    EXPECT_EQ(got.lines[i].index, want.lines[i].index);
    EXPECT_EQ(got.lines[i].direction, want.lines[i].direction);
    EXPECT_EQ(got.lines[i].centroid, want.lines[i].centroid);
  }
}

/// How many plane entries still hold the search of an earlier call.
size_t Kept(const std::vector<CachedSurface>& before, const std::vector<CachedSurface>& after) {
  size_t kept = 0;
  for (size_t i = 0; i < before.size(); ++i) {
    kept += before[i].margin_m >= 0.0 && before[i].query_world == after[i].query_world;
  }
  return kept;
}

class NeighbourCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(7);
    const Cloud map = RandomYard(4000, &rng);
    plane_map_.Insert(map.planes);
    edge_map_.Insert(map.edges);
    scan_ = RandomYard(300, &rng);
  }

  ScanMatcher matcher_;
  VoxelMap plane_map_{{.voxel_m = 0.5, .max_points_per_voxel = 10}};
  VoxelMap edge_map_{{.voxel_m = 0.5, .max_points_per_voxel = 10}};
  Cloud scan_;
};

TEST_F(NeighbourCacheTest, AssociationsAlongAWalkEqualFreshOnesToTheBit) {
  std::mt19937 rng(11);
  NeighbourCache cache;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  size_t kept = 0, entries = 0;
  // Steps from a tenth of a millimetre to 5 cm: some searches are reused, some not.
  for (const double step_m : {1e-4, 1e-3, 5e-3, 0.02, 0.05, 1e-3, 1e-4}) {
    T = T * Step(&rng, step_m, step_m / 10.0);
    const std::vector<CachedSurface> before = cache.planes.For(plane_map_, scan_.planes.size());
    const Associations cached = Associate(matcher_, scan_, plane_map_, edge_map_, T, &cache);
    ExpectSame(cached, Associate(matcher_, scan_, plane_map_, edge_map_, T, nullptr));
    kept += Kept(before, cache.planes.For(plane_map_, scan_.planes.size()));
    entries += scan_.planes.size();
  }
  // Otherwise the equality above would hold trivially.
  EXPECT_GT(kept, entries / 4) << "the cache was hardly ever used";
  EXPECT_LT(kept, entries) << "the larger steps must search again";
}

TEST_F(NeighbourCacheTest, AChangedMapForgetsEverySearch) {
  NeighbourCache cache;
  const Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  Associate(matcher_, scan_, plane_map_, edge_map_, T, &cache);
  const std::vector<CachedSurface> before = cache.planes.For(plane_map_, scan_.planes.size());
  ASSERT_GT(Kept(before, before), 0u);

  // One point right beside a scan feature: it may be that feature's new nearest neighbour.
  const uint64_t revision = plane_map_.revision();
  ASSERT_EQ(plane_map_.Insert({scan_.planes[0] + Eigen::Vector3d(0.01, 0.0, 0.0)}), 1u);
  EXPECT_NE(plane_map_.revision(), revision);
  EXPECT_EQ(Kept(before, cache.planes.For(plane_map_, scan_.planes.size())), 0u);
  ExpectSame(Associate(matcher_, scan_, plane_map_, edge_map_, T, &cache),
             Associate(matcher_, scan_, plane_map_, edge_map_, T, nullptr));
}

TEST_F(NeighbourCacheTest, AnotherMapOrFeatureCountForgetsEverySearch) {
  NeighbourCache cache;
  Associate(matcher_, scan_, plane_map_, edge_map_, Eigen::Isometry3d::Identity(), &cache);
  const std::vector<CachedSurface> before = cache.planes.For(plane_map_, scan_.planes.size());
  const VoxelMap copy = plane_map_;  // the same points, another map
  EXPECT_EQ(Kept(before, cache.planes.For(copy, scan_.planes.size())), 0u);
  cache.planes.For(plane_map_, scan_.planes.size());
  EXPECT_EQ(cache.planes.For(plane_map_, scan_.planes.size() - 1).front().margin_m, -1.0);
}

TEST_F(NeighbourCacheTest, MatchLeavesItsSearchesForTheNextAssociation) {
  std::mt19937 rng(5);
  const Eigen::Isometry3d guess = Step(&rng, 0.1, 0.02);
  NeighbourCache cache;
  const MatchResult with =
      matcher_.Match(scan_.planes, scan_.edges, plane_map_, edge_map_, guess, &cache);
  const MatchResult without =
      matcher_.Match(scan_.planes, scan_.edges, plane_map_, edge_map_, guess);
  EXPECT_EQ(with.T_world_lidar.matrix(), without.T_world_lidar.matrix());
  EXPECT_EQ(with.iterations, without.iterations);
  EXPECT_EQ(with.plane_inliers, without.plane_inliers);
  EXPECT_EQ(with.edge_inliers, without.edge_inliers);
  EXPECT_EQ(with.hessian, without.hessian);
  // And a later association at the result reuses Match's searches.
  const std::vector<CachedSurface> before = cache.planes.For(plane_map_, scan_.planes.size());
  ExpectSame(Associate(matcher_, scan_, plane_map_, edge_map_, with.T_world_lidar, &cache),
             Associate(matcher_, scan_, plane_map_, edge_map_, with.T_world_lidar, nullptr));
  EXPECT_GT(Kept(before, cache.planes.For(plane_map_, scan_.planes.size())), before.size() / 2);
}

}  // namespace
}  // namespace swlio::estimator

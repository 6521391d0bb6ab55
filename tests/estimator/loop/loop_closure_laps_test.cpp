// Loop closure on a patrol (issue 33): the same rectangle driven lap after lap. The keyframe
// store keeps one cloud per place, so its size and bytes stop growing after the first lap,
// while the graph takes every pass and loops keep being found. With places off
// (place_radius_m = 0) the store grows by a lap's clouds per lap.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "box_yard.h"
#include "swlio/estimator/loop/loop_closure.h"
#include "swlio/estimator/map/map_pcd.h"

namespace swlio::estimator {
namespace {

using test::BoxYard;
using test::Cut;
using test::RectangleDrive;
using test::Scene;

struct LapCounts {
  size_t nodes = 0;
  size_t clouds = 0;
  size_t bytes = 0;
  size_t accepted = 0;
  size_t saved_nodes = 0;
};

/// Drives `laps` laps (0.5 s per 0.5 m step, the truth as odometry) and counts after each.
std::vector<LapCounts> DriveLaps(const LoopClosureConfig& config,
                                 int laps,
                                 LoopClosure* driven = nullptr) {
  const Scene scene = BoxYard(7);
  const std::vector<Eigen::Isometry3d> lap = RectangleDrive(0.0);
  LoopClosure own{config};
  LoopClosure& closure = driven != nullptr ? *driven : own;
  std::vector<LapCounts> out;
  int64_t t_ns = 0;
  for (int l = 0; l < laps; ++l) {
    for (const Eigen::Isometry3d& T : lap) {
      KeyframeCloud kf = Cut(scene, t_ns, T);
      kf.T_world_imu = T;
      closure.AddKeyframe(kf);
      t_ns += 500'000'000;
    }
    out.push_back({closure.nodes(), closure.store().clouds(), closure.store().bytes(),
                   closure.stats().accepted, closure.ToSavedMap().nodes.size()});
    std::printf("[ laps ] lap %d: %zu nodes, %zu clouds, %zu kB, %zu loops, %zu map nodes\n", l + 1,
                out.back().nodes, out.back().clouds, out.back().bytes / 1024, out.back().accepted,
                out.back().saved_nodes);
  }
  return out;
}

TEST(LoopClosureLaps, KeyframeStoreStopsGrowingAfterTheFirstLap) {
  const std::vector<LapCounts> c = DriveLaps(LoopClosureConfig{}, 3);
  // The graph takes every pass ...
  EXPECT_GT(c[2].nodes, c[0].nodes + 2 * (c[0].nodes - 10));
  // ... the store and the saved map hold the first lap's places, nothing more.
  EXPECT_EQ(c[2].clouds, c[0].clouds);
  EXPECT_EQ(c[2].bytes, c[0].bytes);
  EXPECT_EQ(c[2].saved_nodes, c[0].clouds);
  // The first lap's end already returns to its start: fewer clouds than nodes.
  EXPECT_LT(c[0].clouds, c[0].nodes);
  // Loops are still found on the later laps (candidates keep their clouds).
  EXPECT_GT(c[2].accepted, c[0].accepted);
}

TEST(LoopClosureLaps, WithoutPlacesTheStoreGrowsEveryLap) {
  LoopClosureConfig config;
  config.place_radius_m = 0.0;
  const std::vector<LapCounts> c = DriveLaps(config, 2);
  EXPECT_EQ(c[1].clouds, c[1].nodes);
  EXPECT_GT(c[1].bytes, c[0].bytes + c[0].bytes / 2);
}

// swliod publishes the map merged straight from the store (LoopClosure::MergedCloud): it must
// be the saved map's cloud to the last bit, loop corrections included.
TEST(LoopClosureLaps, MergedCloudFromTheStoreIsTheSavedMapsCloud) {
  LoopClosure closure{LoopClosureConfig{}};
  const std::vector<LapCounts> c = DriveLaps(LoopClosureConfig{}, 2, &closure);
  ASSERT_GT(c[1].accepted, 0u);  // corrected poses, not only odometry
  EXPECT_EQ(closure.map_nodes(), c[1].saved_nodes);
  for (const double voxel_m : {0.1, 0.37}) {
    std::string error_store, error_saved;
    const auto from_store = closure.MergedCloud(voxel_m, &error_store);
    const auto from_saved = MergedMapCloud(closure.ToSavedMap(), voxel_m, &error_saved);
    ASSERT_TRUE(from_store.has_value()) << error_store;
    ASSERT_TRUE(from_saved.has_value()) << error_saved;
    ASSERT_GT(from_store->size(), 1000u);
    ASSERT_EQ(from_store->size(), from_saved->size());
    for (size_t i = 0; i < from_store->size(); ++i) {
      ASSERT_EQ((*from_store)[i], (*from_saved)[i]) << "point " << i << " at " << voxel_m << " m";
    }
  }
  std::string error;
  EXPECT_FALSE(closure.MergedCloud(0.0, &error).has_value());
  EXPECT_NE(error.find("voxel size"), std::string::npos) << error;
}

}  // namespace
}  // namespace swlio::estimator

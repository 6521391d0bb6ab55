// Moving objects out of the saved map (LoopClosureConfig::visibility, visibility_image.h) and
// out of the local map (VoxelMap::VoteAndRemove, as the window uses it): simulated sweeps of
// `short` with test-side movers (moving_boxes.h: a person crossing, a car passing, a car parked
// then gone, a person walking beside), and with the simulator's own people and vehicles;
// keyframes at the true poses, features from the window's front end. Every feature's label is
// carried by its position: the saved map's points are the features moved back into the world at the
// same poses, so each is looked up to the millimetre.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <unordered_map>

#include "disturb/apply_disturbances.h"
#include "moving_boxes.h"
#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"
#include "swlio/estimator/frontend/front_end.h"
#include "swlio/estimator/loop/loop_closure.h"
#include "swlio/estimator/map/visibility_image.h"
#include "swlio/estimator/registration/voxel_map.h"
#include "swlio/estimator/window/window_estimator_config.h"

namespace swlio::estimator {
namespace {

/// A feature's label: its true surface class, or kMover.
using Label = uint8_t;
constexpr Label kMover = 200;  ///< kMover + the box's index

bool IsThin(Label l) {
  return l == static_cast<Label>(sim::SurfaceClass::kPole) ||
         l == static_cast<Label>(sim::SurfaceClass::kInsulator);
}

/// Labels by world position, to the millimetre.
class LabelIndex {
 public:
  void Add(const Eigen::Vector3d& p_world, Label label) { labels_[Key(p_world)] = label; }
  /// The label of a point within 2 mm of one added (float storage rounds by micrometres);
  /// false when none.
  bool Find(const Eigen::Vector3d& p_world, Label* label) const {
    for (int dx = -2; dx <= 2; ++dx)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dz = -2; dz <= 2; ++dz) {
          const auto it = labels_.find(Key(p_world + 1e-3 * Eigen::Vector3d(dx, dy, dz)));
          if (it != labels_.end()) {
            *label = it->second;
            return true;
          }
        }
    return false;
  }

 private:
  static int64_t Key(const Eigen::Vector3d& p) {
    const auto q = [](double v) { return static_cast<int64_t>(std::llround(v * 1e3)) & 0x1FFFFF; };
    return (q(p.x()) << 42) | (q(p.y()) << 21) | q(p.z());
  }
  std::unordered_map<int64_t, Label> labels_;
};

struct Counts {
  std::array<size_t, 16> per_class{};
  size_t total = 0, mover = 0, static_points = 0, thin = 0, unlabelled = 0;
  double MoverShare() const {
    return total > 0 ? static_cast<double>(mover) / static_cast<double>(total) : 0.0;
  }
};

void Count(const LabelIndex& index, const Eigen::Vector3d& p_world, Counts* c) {
  Label label;
  ++c->total;
  if (!index.Find(p_world, &label)) {
    ++c->unlabelled;
    return;
  }
  c->mover += label >= kMover;
  c->static_points += label < kMover;
  c->thin += IsThin(label);
  ++c->per_class[label >= kMover ? 15 - (label - kMover) : label];
}

Counts CountSavedMap(const SavedMap& map, const LabelIndex& index) {
  Counts c;
  for (const SavedMapNode& n : map.nodes) {
    const Eigen::Isometry3d T = n.T_map_imu * n.T_imu_lidar;
    for (const auto* points : {&n.planes_lidar, &n.edges_lidar}) {
      for (const Eigen::Vector3d& p : *points) Count(index, T * p, &c);
    }
  }
  return c;
}

Counts CountLocalMap(const VoxelMap& planes, const VoxelMap& edges, const LabelIndex& index) {
  Counts c;
  for (const VoxelMap* m : {&planes, &edges}) {
    for (const Eigen::Vector3d& p : m->Points()) Count(index, p, &c);
  }
  return c;
}

/// The window's local maps, as WindowEstimator keeps them (its radius left out: a short drive).
struct LocalMaps {
  explicit LocalMaps(const LidarOdometryConfig& c) : planes(c.plane_map), edges(c.edge_map) {}
  VoxelMap planes, edges;
};

/// The four maps after a drive: keyframes at the true poses from `start_s` on, the boxes
/// injected (none: the simulator's own actors, by LabelledScan::moving).
struct DriveMaps {
  Counts saved_on, saved_off, local_on, local_off;
  size_t keyframes = 0, mover_features = 0;
};

DriveMaps Drive(const sim::SimSetup& setup_ref,
                const std::vector<test::MovingBox>& boxes,
                double start_s) {
  const sim::SimSetup* setup = &setup_ref;

  const WindowEstimatorConfig window = WithWindowFeatures(WindowEstimatorConfig{});
  FrontEnd front_end(window.odometry.front_end);
  FrontEndOutput features;
  const Eigen::Isometry3d T_imu_lidar = setup->lidar.T_imu_lidar;

  LoopClosureConfig on;
  on.enabled = false;  // no loops on this drive: the graph keeps the true poses
  LoopClosureConfig off = on;
  off.visibility.enabled = false;
  LoopClosure with(on), without(off);
  LocalMaps local_with(window.odometry), local_without(window.odometry);
  LabelIndex index;
  size_t mover_features = 0, keyframes = 0;

  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  std::vector<uint16_t> mover;
  std::optional<Eigen::Isometry3d> last;
  while (source.Next(&ls, start_s)) {
    const Eigen::Isometry3d& T_world_lidar = ls.T_world_lidar_end;
    if (last) {
      const Eigen::Isometry3d d = last->inverse() * T_world_lidar;
      if (d.translation().norm() < window.odometry.keyframe_distance_m &&
          Eigen::AngleAxisd(d.linear()).angle() < window.odometry.keyframe_angle_rad)
        continue;
    }
    last = T_world_lidar;
    ++keyframes;
    test::InjectBoxes(*setup, boxes, &ls, &mover);
    front_end.Process(ls.scan, &features);
    KeyframeCloud kf;
    kf.t_ns = ls.scan.t_end_ns;
    kf.T_world_imu = T_world_lidar * T_imu_lidar.inverse();
    kf.T_imu_lidar = T_imu_lidar;
    for (auto [from, to] : {std::pair{&features.features.planes, &kf.planes_lidar},
                            std::pair{&features.features.edges, &kf.edges_lidar}}) {
      for (const FeaturePoint& f : *from) {
        to->push_back(f.xyz_m.cast<double>());
        const sim::SurfaceClass cls = ls.cls[f.source_index];
        if (!ls.moving.empty() && ls.moving[f.source_index] != 0) mover[f.source_index] = 1;
        const Label label = mover[f.source_index] != 0
                                ? static_cast<Label>(kMover + mover[f.source_index] - 1)
                                : static_cast<Label>(cls);
        mover_features += label >= kMover;
        index.Add((kf.T_world_imu * T_imu_lidar) * to->back(), label);
      }
    }
    auto image = std::make_shared<VisibilityImage>(window.visibility);
    image->Build(ls.scan.points, T_world_lidar);
    without.AddKeyframe(kf);
    kf.visibility = image;
    with.AddKeyframe(kf);
    // The local maps: the keyframe's free space first, then its features (window_lidar.cpp).
    const auto test = [&image](const Eigen::Vector3d& p) { return image->Test(p); };
    const auto remove_at = static_cast<int>(window.visibility.votes_to_remove);
    for (VoxelMap* m : {&local_with.planes, &local_with.edges}) {
      m->VoteAndRemove(T_world_lidar.translation(), window.visibility.check_radius_m, remove_at,
                       test);
    }
    for (LocalMaps* m : {&local_with, &local_without}) {
      for (auto [map, points] :
           {std::pair{&m->planes, &kf.planes_lidar}, std::pair{&m->edges, &kf.edges_lidar}}) {
        std::vector<Eigen::Vector3d> world;
        for (const Eigen::Vector3d& p : *points) world.push_back(T_world_lidar * p);
        map->Insert(world);
      }
    }
  }
  DriveMaps out;
  out.keyframes = keyframes;
  out.mover_features = mover_features;
  out.saved_on = CountSavedMap(with.ToSavedMap(), index);
  out.saved_off = CountSavedMap(without.ToSavedMap(), index);
  out.local_on = CountLocalMap(local_with.planes, local_with.edges, index);
  out.local_off = CountLocalMap(local_without.planes, local_without.edges, index);
  std::printf("keyframes %zu, mover features %zu, removed from the stored clouds %zu\n", keyframes,
              mover_features, with.stats().dynamic_removed);
  return out;
}

void ExpectCleanMaps(const DriveMaps& d) {
  ASSERT_GT(d.keyframes, 50u);
  ASSERT_GT(d.mover_features, 500u) << "the movers must be seen";
  const Counts &saved_on = d.saved_on, &saved_off = d.saved_off;
  const Counts &local_on = d.local_on, &local_off = d.local_off;
  for (const auto& [name, c] : {std::pair{"saved map, removal on ", saved_on},
                                std::pair{"saved map, removal off", saved_off},
                                std::pair{"local map, removal on ", local_on},
                                std::pair{"local map, removal off", local_off}}) {
    std::printf("%s: %zu points, %zu on movers (%.2f %%), %zu static (%zu thin), %zu unlabelled\n",
                name, c.total, c.mover, 100.0 * c.MoverShare(), c.static_points, c.thin,
                c.unlabelled);
    for (size_t k = 0; k < c.per_class.size(); ++k) {
      if (c.per_class[k] == 0) continue;
      if (k >= 12) {
        std::printf("  mover%zu %zu", 15 - k, c.per_class[k]);
      } else {
        std::printf("  %s %zu", sim::ClassName(static_cast<sim::SurfaceClass>(k)), c.per_class[k]);
      }
    }
    std::printf("\n");
  }
  EXPECT_EQ(saved_on.unlabelled + saved_off.unlabelled, 0u) << "bookkeeping";
  // Without the removal the movers are in both maps (else this test could not fail).
  EXPECT_GT(saved_off.MoverShare(), 0.01);
  EXPECT_GT(local_off.MoverShare(), 0.01);
  // With it: under 1 % of the saved map on movers (the bound; measured 0.96 %) and
  // under 2 % of the local map (1.56 %: the newest keyframes' movers are in it until a later
  // sweep sees through them); ≥ 98 % of the static points and of the thin structure (poles,
  // insulators) kept.
  EXPECT_LT(saved_on.MoverShare(), 0.01);
  EXPECT_LT(local_on.MoverShare(), 0.02);
  const auto kept = [](size_t on, size_t off) {
    return off > 0 ? static_cast<double>(on) / static_cast<double>(off) : 0.0;
  };
  EXPECT_GE(kept(saved_on.static_points, saved_off.static_points), 0.98);
  EXPECT_GE(kept(saved_on.thin, saved_off.thin), 0.98);
  EXPECT_GE(kept(local_on.static_points, local_off.static_points), 0.98);
  EXPECT_GE(kept(local_on.thin, local_off.thin), 0.98);
}

TEST(LoopClosureVisibility, InjectedMoversLeaveTheMapsAndStaticStructureStays) {
  constexpr double kStartS = 1.0;
  auto setup = sim::MakeSimSetup("short", 1, 26.0, std::nullopt, kStartS);
  ASSERT_TRUE(setup.has_value());
  ExpectCleanMaps(Drive(*setup, test::RouteMovers(*setup, kStartS + 1.0), kStartS));
}

// The simulator's own people and vehicles (swlio-sim --disturb people,vehicles), labelled by
// the simulator (moving: they move at some time during the drive).
TEST(LoopClosureVisibility, SimulatedActorsLeaveTheMapsAndStaticStructureStays) {
  auto setup = sim::MakeSimSetup("short", 1, 30.0);
  ASSERT_TRUE(setup.has_value());
  std::string error;
  const auto actors = sim::ParseDisturbanceList("people,vehicles", &error);
  ASSERT_TRUE(actors.has_value()) << error;
  sim::ApplyDisturbances(&*setup, *actors);
  ExpectCleanMaps(Drive(*setup, {}, 1.0));
}

}  // namespace
}  // namespace swlio::estimator

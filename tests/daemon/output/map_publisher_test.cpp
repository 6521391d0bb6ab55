// The map cloud (map_publisher.h): merged from keyframes at their corrected poses, capped by a
// coarser voxel (then by thinning), published after a loop correction at most once per
// period, and — localizing — the saved map once at start, received over DDS on loopback
// (domain 155) with every point on the scene. The health's "swlio: map" entry.
#include "swlio/daemon/output/map_publisher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <thread>
#include <unordered_map>

#include "box_yard.h"
#include "box_yard_map.h"
#include "swlio/core/time.h"
#include "swlio/daemon/pipeline/localization_thread.h"
#include "swlio/daemon/pipeline/loop_closure_thread.h"
#include "swlio/daemon/runtime/health.h"
#include "swlio/estimator/loop/keyframe_descriptor.h"
#include "swlio/estimator/map/map_pcd.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/point_cloud.h"
#include "swlio/ipc/subscriber.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using Vec3 = Eigen::Vector3d;

estimator::SavedMapNode Node(int64_t t_ns,
                             const Eigen::Isometry3d& T_map_imu,
                             const Eigen::Isometry3d& T_imu_lidar,
                             std::vector<Vec3> planes,
                             std::vector<Vec3> edges) {
  return {t_ns, T_map_imu, T_imu_lidar, std::move(planes), std::move(edges), {}};
}

Eigen::Isometry3d Translation(const Vec3& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = t;
  return T;
}

/// Sorted, so that clouds compare as sets.
std::vector<std::array<float, 3>> Sorted(const std::vector<Eigen::Vector3f>& points) {
  std::vector<std::array<float, 3>> out;
  for (const Eigen::Vector3f& p : points) out.push_back({p.x(), p.y(), p.z()});
  std::sort(out.begin(), out.end());
  return out;
}

TEST(MapCloud, TwoKeyframesLandAtTheirCorrectedPoses) {
  // Node 0 at (10, 0, 0), LiDAR 1 m above the IMU; node 1 at (0, 5, 0) turned 90° left. Node 1
  // sees one of node 0's points again (one voxel). Points sit mid-voxel (x.x5 m), so that
  // rounding cannot move them across a voxel boundary.
  estimator::SavedMap map;
  map.nodes.push_back(Node(1, test::Pose({10, 0, 0}, 0.0), Translation({0, 0, 1}),
                           {{1.05, 0.05, 0.05}}, {{0.05, 2.05, 0.05}}));
  map.nodes.push_back(Node(2, test::Pose({0, 5, 0}, std::numbers::pi / 2),
                           Eigen::Isometry3d::Identity(),
                           {{1.05, -0.05, 0.05}, {-4.95, -11.05, 1.05}}, {{0.05, -0.05, 3.05}}));
  std::string error;
  const std::optional<MapCloud> cloud = BuildMapCloud(map, 1000, 0.0, &error);
  ASSERT_TRUE(cloud) << error;
  EXPECT_EQ(cloud->voxel_m, estimator::kMergedCloudVoxelM);
  EXPECT_EQ(cloud->keep_every, 1u);
  const std::vector<std::array<float, 3>> got = Sorted(cloud->points_map);
  const std::vector<std::array<float, 3>> want = {
      {0.05f, 5.05f, 3.05f}, {0.05f, 6.05f, 0.05f}, {10.05f, 2.05f, 1.05f}, {11.05f, 0.05f, 1.05f}};
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    for (size_t a = 0; a < 3; ++a) EXPECT_NEAR(got[i][a], want[i][a], 1e-5) << i << " " << a;
  }

  const ipc::PointCloud2 msg = ToPointCloud2(cloud->points_map, 42, "map");
  EXPECT_EQ(msg.t_ns, 42);
  EXPECT_EQ(msg.frame_id, "map");
  EXPECT_EQ(msg.height, 1u);
  EXPECT_EQ(msg.width, 4u);
  EXPECT_EQ(msg.point_step, 12u);
  EXPECT_EQ(msg.row_step, 48u);
  EXPECT_EQ(msg.data.size(), 48u);
  ASSERT_TRUE(ipc::HasXyzLayout(msg));
  for (size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3f& p = cloud->points_map[i];
    EXPECT_EQ(ipc::XyzAt(msg, i), (std::array<float, 3>{p.x(), p.y(), p.z()}));
  }
}

TEST(MapCloud, ObeysThePointCapWithACoarserVoxel) {
  // A 3 m × 3 m plane sampled every 5 cm: 900 voxels of 0.1 m, 200 allowed.
  std::vector<Vec3> plane;
  for (int i = 0; i < 60; ++i) {
    for (int j = 0; j < 60; ++j) plane.emplace_back(0.025 + 0.05 * i, 0.025 + 0.05 * j, 0.5);
  }
  estimator::SavedMap map;
  map.nodes.push_back(
      Node(1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), plane, {}));
  std::string error;
  const std::optional<MapCloud> fine = BuildMapCloud(map, 1000, 0.0, &error);
  ASSERT_TRUE(fine) << error;
  EXPECT_EQ(fine->points_map.size(), 900u);
  const std::optional<MapCloud> capped = BuildMapCloud(map, 200, 0.0, &error);
  ASSERT_TRUE(capped) << error;
  EXPECT_LE(capped->points_map.size(), 200u);
  EXPECT_GT(capped->points_map.size(), 100u);  // coarser, not emptied
  EXPECT_GT(capped->voxel_m, estimator::kMergedCloudVoxelM);
  EXPECT_EQ(capped->keep_every, 1u);  // the voxel alone did it
  EXPECT_GE(capped->builds, 2);
  // Starting from the voxel a previous build needed takes one build.
  const std::optional<MapCloud> again = BuildMapCloud(map, 200, capped->voxel_m, &error);
  ASSERT_TRUE(again) << error;
  EXPECT_EQ(again->builds, 1);
  EXPECT_EQ(again->points_map.size(), capped->points_map.size());
}

TEST(MapCloud, ThinsWhenNoReasonableVoxelFitsTheCap) {
  // 3000 points 1 km apart: every voxel of a few metres holds one, so only thinning helps.
  std::vector<Vec3> far;
  for (int i = 0; i < 3000; ++i) far.emplace_back(1000.0 * i, 0.0, 0.0);
  estimator::SavedMap map;
  map.nodes.push_back(
      Node(1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), far, {}));
  std::string error;
  const std::optional<MapCloud> cloud = BuildMapCloud(map, 1000, 0.0, &error);
  ASSERT_TRUE(cloud) << error;
  EXPECT_EQ(cloud->builds, kMaxVoxelSteps + 1);
  EXPECT_EQ(cloud->keep_every, 3u);
  EXPECT_EQ(cloud->points_map.size(), 1000u);
}

TEST(MapPublisher, PublishesAChangedMapAtMostOncePerPeriod) {
  estimator::SavedMap map;
  map.nodes.push_back(Node(1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(),
                           {{1, 2, 3}, {4, 5, 6}}, {{7, 8, 9}}));
  MapPublisher publisher(nullptr, "map", 1000, 3600.0);
  const int64_t now = MonotonicNowNs();
  EXPECT_FALSE(publisher.Due(now));  // nothing changed yet
  publisher.MarkChanged();
  EXPECT_TRUE(publisher.Due(now));
  ASSERT_TRUE(publisher.Publish(map, Watchdog::Handle{}, 1.5));
  MapPublishCounters c = publisher.counters();
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.published, 1u);
  EXPECT_EQ(c.failures, 0u);
  EXPECT_EQ(c.points, 3u);
  EXPECT_EQ(c.bytes, 36u);
  EXPECT_EQ(c.voxel_m, estimator::kMergedCloudVoxelM);
  EXPECT_GE(c.build_ms, 1.5);
  EXPECT_FALSE(publisher.Due(MonotonicNowNs()));
  publisher.MarkChanged();
  EXPECT_FALSE(publisher.Due(MonotonicNowNs()));  // within the period
  EXPECT_TRUE(publisher.Due(MonotonicNowNs() + SecToNs(3601.0)));
}

TEST(MapPublisher, ASlowBuildStretchesThePeriod) {
  estimator::SavedMap map;
  map.nodes.push_back(
      Node(1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), {{1, 2, 3}}, {}));
  MapPublisher publisher(nullptr, "map", 1000, 0.001);
  publisher.MarkChanged();
  const int64_t t0 = MonotonicNowNs();
  ASSERT_TRUE(publisher.Publish(map, Watchdog::Handle{}, 100.0));  // a 100 ms snapshot
  publisher.MarkChanged();
  EXPECT_FALSE(publisher.Due(t0 + SecToNs(1.9)));  // the period is 1 ms, 20 × 100 ms wins
  EXPECT_TRUE(publisher.Due(MonotonicNowNs() + SecToNs(2.1)));
}

ipc::DiagnosticStatus MapHealth(const MapPublishCounters& c) {
  HealthSnapshot s;
  s.map = c;
  HealthReporter health;
  for (const ipc::DiagnosticStatus& d : health.Diagnostics(s).status) {
    if (d.name == "swlio: map") return d;
  }
  ADD_FAILURE() << "no \"swlio: map\" status";
  return {};
}

std::string Value(const ipc::DiagnosticStatus& d, const std::string& key) {
  for (const ipc::KeyValue& kv : d.values) {
    if (kv.key == key) return kv.value;
  }
  return "(missing)";
}

TEST(MapPublisher, ARefusedMapIsCountedAndWarnedAbout) {
  estimator::SavedMap map;
  map.nodes.push_back(
      Node(1, Translation({2e9, 0, 0}), Eigen::Isometry3d::Identity(), {{1, 0, 0}}, {}));
  MapPublisher publisher(nullptr, "map", 1000, 10.0);
  EXPECT_FALSE(publisher.Publish(map, Watchdog::Handle{}));
  const MapPublishCounters c = publisher.counters();
  EXPECT_EQ(c.published, 0u);
  EXPECT_EQ(c.failures, 1u);
  EXPECT_TRUE(c.last_failed);
  EXPECT_EQ(MapHealth(c).level, ipc::DiagnosticLevel::kWarn);

  MapPublishCounters ok;
  ok.enabled = true;
  ok.published = 3;
  ok.points = 123456;
  ok.bytes = 1481472;
  ok.voxel_m = 0.1;
  ok.build_ms = 250.0;
  const ipc::DiagnosticStatus d = MapHealth(ok);
  EXPECT_EQ(d.level, ipc::DiagnosticLevel::kOk);
  EXPECT_EQ(Value(d, "maps_published"), "3");
  EXPECT_EQ(Value(d, "points"), "123456");
  EXPECT_EQ(Value(d, "bytes"), "1481472");
  EXPECT_EQ(Value(d, "build_ms"), "250.0");
  HealthSnapshot off;  // map publishing off: no entry
  HealthReporter health;
  for (const ipc::DiagnosticStatus& s : health.Diagnostics(off).status)
    EXPECT_NE(s.name, "swlio: map");
}

/// Feeds the drifted box-yard drive of LoopClosureThread's test, its first `n` keyframes (all
/// for n = 0); returns how many.
size_t DriveDrifted(size_t n, SpscQueue<KeyframePtr>* keyframes) {
  const test::Scene scene = test::BoxYard(7);
  const std::vector<Eigen::Isometry3d> truth = test::RectangleDrive(12.0);
  const Eigen::Isometry3d drift = test::Pose({0.002, 0.0, 0.001}, 2.5e-4);
  Eigen::Isometry3d odom = truth[0];
  n = n == 0 ? truth.size() : std::min(n, truth.size());
  for (size_t k = 0; k < n; ++k) {
    if (k > 0) odom = odom * truth[k - 1].inverse() * truth[k] * drift;
    auto kf = std::make_shared<estimator::KeyframeCloud>(
        test::Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]));
    kf->T_world_imu = odom;
    EXPECT_TRUE(keyframes->Push(KeyframePtr(std::move(kf))));
  }
  return n;
}

/// Runs a loop-closure thread with a map publisher (publication period `period_s`) over the
/// drive's first `n` keyframes; waits for the first map, then for one due after the last solve.
std::pair<LoopClosureCounters, MapPublishCounters> RunLoopClosure(size_t n, double period_s) {
  SpscQueue<KeyframePtr> keyframes{"keyframes", "test", "loop_closure", 512};
  SpscQueue<MapCorrection> corrections{"corrections", "loop_closure", "test", 16};
  LoopClosureThread thread(estimator::LoopClosureConfig{}, {&keyframes, &corrections});
  MapPublisher map(nullptr, "map", 500'000, period_s);
  thread.PublishMapTo(&map);
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });
  n = DriveDrifted(n, &keyframes);
  for (int i = 0; i < 600 && thread.counters().keyframes < n; ++i)  // ≤ 60 s: sanitizers
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  // The last keyframe's solve, then Run's next passes publish what is due.
  for (int i = 0; i < 100 && map.counters().published == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a map due after the last solve
  stop = true;
  runner.join();
  return {thread.counters(), map.counters()};
}

TEST(MapPublisher, LoopClosurePublishesTheGrowingMapAtMostOncePerPeriod) {
  // The first 100 keyframes (50 m) close no loop; the map grows, and its first node makes a
  // map due at once: one map (the hour-long period holds back the rest).
  const auto [open_loop, first_map] = RunLoopClosure(100, 3600.0);
  EXPECT_EQ(open_loop.accepted, 0u);
  EXPECT_EQ(first_map.published, 1u);
  EXPECT_EQ(first_map.failures, 0u);
  EXPECT_GT(first_map.points, 0u);
  // The whole drive with a short period: maps while it grows and after its corrections.
  const auto [closed, map] = RunLoopClosure(0, 0.05);
  ASSERT_GE(closed.accepted, 1u);
  EXPECT_GE(map.published, 2u);
  EXPECT_EQ(map.failures, 0u);
  EXPECT_GT(map.points, first_map.points);
  EXPECT_GT(map.points, 1000u);
  EXPECT_EQ(map.bytes, 12 * map.points);
}

using test::BoxYardMap;

/// The scene's points by 0.1 m cell, for nearest-point queries.
class SceneIndex {
 public:
  explicit SceneIndex(const test::Scene& scene) {
    for (const auto* points : {&scene.planes, &scene.edges}) {
      for (const Vec3& p : *points) cells_[Key(Cell(p))].push_back(p);
    }
  }
  /// Distance to the nearest scene point, or 1 m when none is within 0.1 m.
  double Nearest(const Vec3& q) const {
    double best = 1.0;
    const Eigen::Vector3i c = Cell(q);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(Key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const Vec3& p : it->second) best = std::min(best, (p - q).norm());
        }
    return best;
  }

 private:
  static Eigen::Vector3i Cell(const Vec3& p) { return (p / 0.1).array().floor().cast<int>(); }
  static int64_t Key(const Eigen::Vector3i& c) {
    return (int64_t{c.x()} + 100'000) * 1'000'000'000LL + (int64_t{c.y()} + 100'000) * 10'000LL +
           (c.z() + 5'000);
  }
  std::unordered_map<int64_t, std::vector<Vec3>> cells_;
};

TEST(MapPublisher, LocalizationPublishesTheSavedMapOnceOverDds) {
  ipc::IpcConfig ipc;
  ipc.domain_id = 155;
  ipc.dds_config_file = (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string();
  std::string error;
  auto participant = ipc::Participant::Create(ipc, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = ipc::Publisher::Create(*participant, ipc, &error);
  ASSERT_NE(publisher, nullptr) << error;

  const test::Scene scene = test::BoxYard(7);
  SpscQueue<KeyframePtr> keyframes{"keyframes", "test", "localization", 16};
  SpscQueue<MapCorrection> corrections{"corrections", "localization", "test", 16};
  LocalizationThread thread(BoxYardMap(scene), estimator::LocalizationConfig{},
                            {&keyframes, &corrections});
  MapPublisher map(publisher.get(), "map", 500'000, 10.0);
  thread.PublishMapTo(&map);
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });
  for (int i = 0; i < 600 && map.counters().published == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // no second one comes
  stop = true;
  runner.join();
  const MapPublishCounters c = map.counters();
  ASSERT_EQ(c.published, 1u);

  // A subscriber that joins afterwards gets it (latched), in the map frame, on the scene.
  ipc::SubscriberOptions options;
  options.topics = {false, false, false, false, true};
  auto subscriber = ipc::Subscriber::Create(*participant, ipc, options, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  std::vector<ipc::Received<ipc::PointCloud2>> got;
  for (int i = 0; i < 200 && got.empty(); ++i) {
    subscriber->Wait(100'000'000);
    got = subscriber->TakeMaps();
  }
  ASSERT_EQ(got.size(), 1u);
  const ipc::PointCloud2& cloud = got[0].msg;
  EXPECT_EQ(cloud.frame_id, "map");
  EXPECT_EQ(cloud.width, c.points);
  EXPECT_EQ(cloud.data.size(), c.bytes);
  ASSERT_TRUE(ipc::HasXyzLayout(cloud));
  const SceneIndex index(scene);
  // A voxel's centroid sits on its scene point (copies of one point from many keyframes), or
  // between two scene points that share the voxel (box corners, touching boxes).
  size_t on_scene = 0;
  double worst_m = 0.0;
  for (size_t i = 0; i < cloud.width; ++i) {
    const std::array<float, 3> p = ipc::XyzAt(cloud, i);
    const double d = index.Nearest(Vec3(p[0], p[1], p[2]));
    on_scene += d < 0.05 ? 1 : 0;
    worst_m = std::max(worst_m, d);
  }
  EXPECT_GT(static_cast<double>(on_scene), 0.999 * cloud.width)
      << on_scene << " of " << cloud.width;
  EXPECT_LT(worst_m, 0.1);
}

}  // namespace
}  // namespace swlio::daemon

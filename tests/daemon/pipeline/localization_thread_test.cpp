// The localization thread: a saved map of the synthetic box yard, then keyframes of a second
// drive whose odometry has its own frame go in through the optimizer's queue; the first
// correction out jumps (the relocalization), the later ones are to be followed; the counters
// and the health entry say so. And the loop-closure thread's graph saved as a map loads back.
#include "swlio/daemon/pipeline/localization_thread.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <thread>

#include "box_yard.h"
#include "box_yard_map.h"
#include "swlio/daemon/runtime/health.h"
#include "swlio/estimator/loop/keyframe_descriptor.h"

namespace swlio::daemon {
namespace {

using test::BoxYardMap;

void WaitForKeyframes(const LocalizationThread& t, uint64_t n) {
  for (int i = 0; i < 1200 && t.counters().keyframes < n; ++i)  // ≤ 120 s under sanitizers
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

TEST(LocalizationThread, JumpsOnceIntoTheMapThenHandsOverTrackingCorrections) {
  const test::Scene scene = test::BoxYard(7);
  SpscQueue<KeyframePtr> keyframes{"keyframes", "test", "localization", 256};
  SpscQueue<MapCorrection> corrections{"corrections", "localization", "test", 64};
  LocalizationThread thread(BoxYardMap(scene), estimator::LocalizationConfig{},
                            {&keyframes, &corrections});
  EXPECT_EQ(thread.counters().state, estimator::LocalizationState::kRelocalizing);
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });
  const Eigen::Isometry3d T_odom_world = test::Pose({12.0, -7.0, 0.0}, -0.8);
  const std::vector<Eigen::Isometry3d> truth = test::RectangleDrive(0.0);
  const size_t n = 30;
  for (size_t k = 40; k < 40 + n; ++k) {
    auto kf = std::make_shared<estimator::KeyframeCloud>(
        test::Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]));
    kf->T_world_imu = T_odom_world * truth[k];
    ASSERT_TRUE(keyframes.Push(KeyframePtr(std::move(kf))));
  }
  WaitForKeyframes(thread, n);
  stop = true;
  runner.join();

  const LocalizationCounters c = thread.counters();
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.keyframes, n);
  EXPECT_EQ(c.state, estimator::LocalizationState::kTracking);
  EXPECT_EQ(c.hypotheses, 1u);
  EXPECT_GE(c.localized_t_ns, 40 * 500'000'000LL);
  std::vector<MapCorrection> out;
  for (MapCorrection m; corrections.Pop(&m);) out.push_back(m);
  ASSERT_GE(out.size(), 2u);
  EXPECT_TRUE(out.front().jump);
  for (size_t i = 1; i < out.size(); ++i) EXPECT_FALSE(out[i].jump) << i;
  const Eigen::Isometry3d T_map_odom_true = T_odom_world.inverse();
  EXPECT_LT((out.back().T_map_odom.translation() - T_map_odom_true.translation()).norm(), 0.05);

  HealthSnapshot s;
  s.localization = c;
  HealthReporter health;
  const ipc::DiagnosticArray a = health.Diagnostics(s);
  const auto entry = std::find_if(a.status.begin(), a.status.end(),
                                  [](const auto& d) { return d.name == "swlio: localization"; });
  ASSERT_NE(entry, a.status.end());
  EXPECT_EQ(entry->level, ipc::DiagnosticLevel::kOk);
}

TEST(LocalizationThread, HealthWarnsUntilLocalized) {
  HealthSnapshot s;
  s.localization.enabled = true;
  HealthReporter health;
  const ipc::DiagnosticArray a = health.Diagnostics(s);
  const auto entry = std::find_if(a.status.begin(), a.status.end(),
                                  [](const auto& d) { return d.name == "swlio: localization"; });
  ASSERT_NE(entry, a.status.end());
  EXPECT_EQ(entry->level, ipc::DiagnosticLevel::kWarn);
  EXPECT_NE(entry->message.find("no pose published"), std::string::npos) << entry->message;
}

TEST(LoopClosureThread, SavesItsGraphAsAMapThatLoadsBack) {
  SpscQueue<KeyframePtr> keyframes{"keyframes", "test", "loop_closure", 512};
  SpscQueue<MapCorrection> corrections{"corrections", "loop_closure", "test", 16};
  LoopClosureThread thread(estimator::LoopClosureConfig{}, {&keyframes, &corrections});
  const test::Scene scene = test::BoxYard(7);
  const std::vector<Eigen::Isometry3d> truth = test::RectangleDrive(0.0);
  for (size_t k = 0; k < 40; ++k) {
    ASSERT_TRUE(keyframes.Push(std::make_shared<const estimator::KeyframeCloud>(
        test::Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]))));
  }
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });
  for (int i = 0; i < 600 && thread.counters().keyframes < 40; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  stop = true;
  runner.join();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("swlio_map_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string error;
  const size_t nodes =
      thread.SaveMap((dir / "m.swlmap").string(), (dir / "m.pcd").string(), &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_EQ(nodes, thread.counters().nodes);
  const auto map = estimator::LoadMapFile((dir / "m.swlmap").string(), &error);
  ASSERT_TRUE(map.has_value()) << error;
  EXPECT_EQ(map->nodes.size(), nodes);
  EXPECT_GT(std::filesystem::file_size(dir / "m.pcd"), 1000u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace swlio::daemon

// The loop-closure thread: keyframes of a drifted drive around the synthetic box yard go in
// through the optimizer's queue; the loop is found and the correction comes out for the
// publisher; its counters say so.
#include "swlio/daemon/pipeline/loop_closure_thread.h"

#include <gtest/gtest.h>

#include <thread>

#include "box_yard.h"

namespace swlio::daemon {
namespace {

TEST(LoopClosureThread, ClosesTheLoopOfADriftedDriveAndHandsOverTheCorrection) {
  SpscQueue<KeyframePtr> keyframes{"keyframes", "test", "loop_closure", 512};
  SpscQueue<MapCorrection> corrections{"corrections", "loop_closure", "test", 16};
  LoopClosureThread thread(estimator::LoopClosureConfig{}, {&keyframes, &corrections});
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });

  const test::Scene scene = test::BoxYard(7);
  const std::vector<Eigen::Isometry3d> truth = test::RectangleDrive(12.0);
  const Eigen::Isometry3d drift = test::Pose({0.002, 0.0, 0.001}, 2.5e-4);
  Eigen::Isometry3d odom = truth[0];
  for (size_t k = 0; k < truth.size(); ++k) {
    if (k > 0) odom = odom * truth[k - 1].inverse() * truth[k] * drift;
    auto kf = std::make_shared<estimator::KeyframeCloud>(
        test::Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]));
    kf->T_world_imu = odom;
    ASSERT_TRUE(keyframes.Push(KeyframePtr(std::move(kf))));
  }
  // Wait (at most 60 s: under the sanitizers) until every keyframe has been taken.
  for (int i = 0; i < 600 && thread.counters().keyframes < truth.size(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  stop = true;
  runner.join();

  const LoopClosureCounters c = thread.counters();
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.keyframes, truth.size());
  EXPECT_GT(c.nodes, 100u);
  EXPECT_GE(c.accepted, 1u);
  EXPECT_GT(c.correction_m, 0.5);
  MapCorrection last, m;
  size_t n = 0;
  while (corrections.Pop(&m)) {
    last = m;
    ++n;
  }
  ASSERT_GE(n, 1u);
  const Eigen::Vector3d corrected = (last.T_map_odom * odom).translation();
  EXPECT_LT((corrected - truth.back().translation()).norm(), 0.1);
  // The corrected path: one pose per graph node (at that loop), each near its truth.
  ASSERT_NE(last.path, nullptr);
  EXPECT_GT(last.path->size(), 100u);
  EXPECT_LE(last.path->size(), c.nodes);
  double worst_m = 0.0;
  for (const estimator::MapNode& n : *last.path) {
    const Eigen::Vector3d p = truth[static_cast<size_t>(n.t_ns / 500'000'000)].translation();
    worst_m = std::max(worst_m, (n.T_map_imu.translation() - p).norm());
  }
  EXPECT_LT(worst_m, 0.25);  // as in LoopClosure.ClosesADriftedLoopOntoTheTruth
  EXPECT_GT((odom.translation() - truth.back().translation()).norm(), 1.0);
}

}  // namespace
}  // namespace swlio::daemon

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

// While mapping, an operator's pose hint (swlioctl relocalize, /initialpose) re-anchors the map
// frame: the reply says so, the correction jumps, and base_link at the newest keyframe is where
// the hint put it (the base 0.5 m behind the IMU here).
TEST(LoopClosureThread, APoseHintReanchorsTheMapBeingBuilt) {
  SpscQueue<KeyframePtr> keyframes{"keyframes", "test", "loop_closure", 512};
  SpscQueue<MapCorrection> corrections{"corrections", "loop_closure", "test", 16};
  LoopClosureThread thread(estimator::LoopClosureConfig{}, {&keyframes, &corrections});
  Eigen::Isometry3d T_base_imu = Eigen::Isometry3d::Identity();
  T_base_imu.translation() << 0.5, 0.0, 0.3;
  thread.SetBaseFrame(T_base_imu);
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });
  const test::Scene scene = test::BoxYard(7);
  const std::vector<Eigen::Isometry3d> truth = test::RectangleDrive(0.0);
  for (size_t k = 0; k < 15; ++k) {
    auto kf = std::make_shared<estimator::KeyframeCloud>(
        test::Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]));
    kf->T_world_imu = truth[k];
    ASSERT_TRUE(keyframes.Push(KeyframePtr(std::move(kf))));
  }
  for (int i = 0; i < 600 && thread.counters().keyframes < 15; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  PoseHint hint;
  hint.source = "swlioctl";
  hint.x_m = 100.0;
  hint.y_m = 50.0;
  hint.yaw_rad = 1.5;
  hint.command = std::make_shared<PendingCommand>(
      control::Request{control::Command::kRelocalize, "100 50 85.9"});
  ASSERT_TRUE(thread.RequestHint(hint));
  std::optional<control::Reply> reply;
  for (int i = 0; i < 600 && !(reply = hint.command->Result()); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stop = true;
  runner.join();
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->status, control::ReplyStatus::kOk) << reply->message;
  EXPECT_NE(reply->message.find("re-anchored"), std::string::npos) << reply->message;
  MapCorrection last, m;
  while (corrections.Pop(&m)) last = m;
  EXPECT_TRUE(last.jump);
  const Eigen::Isometry3d T_map_base = last.T_map_odom * truth[14] * T_base_imu.inverse();
  EXPECT_NEAR(T_map_base.translation().x(), 100.0, 1e-6);
  EXPECT_NEAR(T_map_base.translation().y(), 50.0, 1e-6);
  EXPECT_NEAR(std::atan2(T_map_base.linear()(1, 0), T_map_base.linear()(0, 0)), 1.5, 1e-6);
  ASSERT_NE(last.path, nullptr);
  EXPECT_EQ(thread.counters().hints, 1u);
  EXPECT_EQ(thread.counters().hints_refused, 0u);
}

}  // namespace
}  // namespace swlio::daemon

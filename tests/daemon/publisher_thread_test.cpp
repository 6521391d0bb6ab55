// The publisher thread's keyframe path: bounded to the newest path_max_poses keyframes, in
// order (without a bound it grew with every lap of a soak).

#include "swlio/daemon/publisher_thread.h"

#include <gtest/gtest.h>

#include <atomic>
#include <limits>

namespace swlio::daemon {
namespace {

TEST(PublisherThread, KeyframePathKeepsTheNewestKeyframesOnly) {
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 16);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 64);
  Doorbell bell;
  PublisherThread publisher(nullptr, FrameIds{}, PublisherQueues{&poses, &odometry, &bell}, {},
                            nullptr, 1'000'000'000, 10);
  for (int i = 0; i < 30; ++i) {
    SweepEstimate e;
    e.status = estimator::OdometryStatus::kTracking;
    e.state.t_ns = (i + 1) * 100'000'000LL;
    e.state.T_world_imu.translation() = Eigen::Vector3d(i, 0.0, 0.0);
    e.keyframe = i % 2 == 0;  // 15 keyframes
    ASSERT_TRUE(odometry.Push(e));
  }
  const std::atomic<bool> stop{true};  // Run only drains what is queued
  publisher.Run(stop, Watchdog::Handle{});
  EXPECT_EQ(publisher.counters().odometry, 30u);
  const auto& path = publisher.keyframes();
  ASSERT_EQ(path.size(), 10u);
  EXPECT_DOUBLE_EQ(path.front().pose.position_m[0], 10.0);  // keyframes 10, 12, …, 28
  EXPECT_DOUBLE_EQ(path.back().pose.position_m[0], 28.0);
}

TEST(PublisherThread, NonFiniteStatesAreNeverPublishedButCounted) {
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 16);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 16);
  Doorbell bell;
  PublisherThread publisher(nullptr, FrameIds{}, PublisherQueues{&poses, &odometry, &bell}, {},
                            nullptr);
  ImuRatePose good;
  good.state.t_ns = 1'000'000;
  ImuRatePose bad = good;
  bad.state.T_world_imu.translation().x() = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(poses.Push(good));
  ASSERT_TRUE(poses.Push(bad));
  SweepEstimate e;
  e.status = estimator::OdometryStatus::kTracking;
  e.state = bad.state;
  ASSERT_TRUE(odometry.Push(e));
  const std::atomic<bool> stop{true};
  publisher.Run(stop, Watchdog::Handle{});
  const PublisherCounters c = publisher.counters();
  EXPECT_EQ(c.poses, 1u);
  EXPECT_EQ(c.odometry, 0u);
  EXPECT_EQ(c.non_finite, 2u);
}

}  // namespace
}  // namespace swlio::daemon

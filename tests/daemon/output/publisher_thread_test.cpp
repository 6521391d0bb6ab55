// The publisher thread: the keyframe path bounded to the newest path_max_poses keyframes, in
// order (without a bound it grew with every lap of a soak); non-finite states never published;
// map corrections followed at a bounded rate.

#include "swlio/daemon/output/publisher_thread.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <limits>

namespace swlio::daemon {
namespace {

TEST(PublisherThread, KeyframePathKeepsTheNewestKeyframesOnly) {
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 16);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 64);
  Doorbell bell;
  PublisherThread publisher(nullptr, OutputFrames{}, PublisherQueues{&poses, &odometry, &bell}, {},
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
  PublisherThread publisher(nullptr, OutputFrames{}, PublisherQueues{&poses, &odometry, &bell}, {},
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

// A map correction of 1 m from the loop-closure thread reaches the output at 0.2 m/s: the
// published keyframe path (poses as published) walks over to the corrected place in 5 s.
TEST(PublisherThread, AMapCorrectionIsFollowedAtTheConfiguredRate) {
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 16);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 128);
  SpscQueue<MapCorrection> corrections("corrections", "test", "publisher", 4);
  Doorbell bell;
  PublisherThread publisher(nullptr, OutputFrames{},
                            PublisherQueues{&poses, &odometry, &bell, &corrections}, {}, nullptr,
                            1'000'000'000, 100, {.max_rate_mps = 0.2, .max_rate_radps = 0.05});
  MapCorrection c;
  c.T_map_odom.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  ASSERT_TRUE(corrections.Push(c));
  for (int i = 0; i < 80; ++i) {  // 8 s at 10 Hz, standing at x = 50 m
    SweepEstimate e;
    e.status = estimator::OdometryStatus::kTracking;
    e.state.t_ns = (i + 1) * 100'000'000LL;
    e.state.T_world_imu.translation() = Eigen::Vector3d(50.0, 0.0, 0.0);
    e.keyframe = true;
    ASSERT_TRUE(odometry.Push(e));
  }
  const std::atomic<bool> stop{true};
  publisher.Run(stop, Watchdog::Handle{});
  const auto& path = publisher.keyframes();
  ASSERT_EQ(path.size(), 80u);
  for (size_t k = 0; k < path.size(); ++k) {
    const double want = 50.0 + std::min(1.0, 0.02 * static_cast<double>(k));
    EXPECT_NEAR(path[k].pose.position_m[0], want, 1e-9) << k;
  }
}

// After a loop the keyframe path becomes the graph's corrected nodes (the newest
// path_max_poses of them); keyframes after it are appended as published.
TEST(PublisherThread, ALoopReplacesTheKeyframePathByTheCorrectedNodes) {
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 4);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 16);
  SpscQueue<MapCorrection> corrections("corrections", "test", "publisher", 4);
  Doorbell bell;
  PublisherThread publisher(nullptr, OutputFrames{},
                            PublisherQueues{&poses, &odometry, &bell, &corrections}, {}, nullptr,
                            1'000'000'000, 4);
  auto nodes = std::make_shared<std::vector<estimator::MapNode>>();
  for (int i = 0; i < 6; ++i) {
    estimator::MapNode n;
    n.t_ns = (i + 1) * 1'000'000'000LL;
    n.T_map_imu.translation() = Eigen::Vector3d(i, 0.5, 0.0);
    nodes->push_back(n);
  }
  MapCorrection c;  // identity correction: the output itself is not moved
  c.path = nodes;
  ASSERT_TRUE(corrections.Push(c));
  SweepEstimate e;
  e.status = estimator::OdometryStatus::kTracking;
  e.state.t_ns = 7'000'000'000;
  e.state.T_world_imu.translation() = Eigen::Vector3d(6.0, 0.0, 0.0);
  e.keyframe = true;
  ASSERT_TRUE(odometry.Push(e));
  const std::atomic<bool> stop{true};
  publisher.Run(stop, Watchdog::Handle{});
  const auto& path = publisher.keyframes();
  ASSERT_EQ(path.size(), 4u);  // nodes 3, 4, 5 (of the newest 4), then the new keyframe
  EXPECT_DOUBLE_EQ(path[0].pose.position_m[0], 3.0);
  EXPECT_DOUBLE_EQ(path[0].pose.position_m[1], 0.5);
  EXPECT_EQ(path[0].t_ns, 4'000'000'000);
  EXPECT_DOUBLE_EQ(path[2].pose.position_m[0], 5.0);
  EXPECT_DOUBLE_EQ(path[3].pose.position_m[0], 6.0);
  EXPECT_DOUBLE_EQ(path[3].pose.position_m[1], 0.0);
}

// Without loop closure (no corrections queue) the poses go out exactly as estimated.
TEST(PublisherThread, WithoutCorrectionsPosesAreUntouched) {
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 4);
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 4);
  Doorbell bell;
  PublisherThread publisher(nullptr, OutputFrames{}, PublisherQueues{&poses, &odometry, &bell}, {},
                            nullptr, 1'000'000'000, 10);
  SweepEstimate e;
  e.status = estimator::OdometryStatus::kTracking;
  e.state.t_ns = 100'000'000;
  e.state.T_world_imu.translation() = Eigen::Vector3d(0.1 + 0.2, 1.0 / 3.0, -7.0);
  e.keyframe = true;
  ASSERT_TRUE(odometry.Push(e));
  const std::atomic<bool> stop{true};
  publisher.Run(stop, Watchdog::Handle{});
  ASSERT_EQ(publisher.keyframes().size(), 1u);
  EXPECT_EQ(publisher.keyframes().front().pose.position_m[0], 0.1 + 0.2);
  EXPECT_EQ(publisher.keyframes().front().pose.position_m[1], 1.0 / 3.0);
}

/// The stamp a keyframe's odometry at daemon time `t_ns` is published with.
int64_t PublishedStamp(int64_t t_ns, StampClock* stamps, const TimeScale& time = {}) {
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 4);
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 4);
  Doorbell bell;
  PublisherThread publisher(nullptr, OutputFrames{}, PublisherQueues{&poses, &odometry, &bell},
                            time, nullptr, 1'000'000'000, 10);
  if (stamps != nullptr) publisher.StampWith(stamps);
  SweepEstimate e;
  e.status = estimator::OdometryStatus::kTracking;
  e.state.t_ns = t_ns;
  e.keyframe = true;
  EXPECT_TRUE(odometry.Push(e));
  const std::atomic<bool> stop{true};
  publisher.Run(stop, Watchdog::Handle{});
  EXPECT_EQ(publisher.counters().odometry, 1u);
  return publisher.keyframes().empty() ? -1 : publisher.keyframes().front().t_ns;
}

// ROS time: the daemon's time (back on the host clock) plus realtime − monotonic; in monotonic
// mode exactly what was published without a StampClock.
TEST(PublisherThread, StampsAreTheStampClocksConversionOfHostTime) {
  constexpr int64_t kOffsetNs = 1'780'000'000'000'000'000 - 100'000'000'000;
  const ClockSources clocks{[] { return int64_t{100'000'000'000}; },
                            [] { return int64_t{1'780'000'000'000'000'000}; }};
  StampClock realtime(true, clocks);
  StampClock monotonic(false, clocks);
  EXPECT_EQ(PublishedStamp(123'456'789'012, &realtime), 123'456'789'012 + kOffsetNs);
  EXPECT_EQ(PublishedStamp(123'456'789'012, &monotonic), 123'456'789'012);
  EXPECT_EQ(PublishedStamp(123'456'789'012, nullptr), 123'456'789'012);
  const TimeScale twice{100'000'000'000, 2.0};  // a simulator at 2x: daemon time runs 2x
  EXPECT_EQ(PublishedStamp(104'000'000'000, &realtime, twice), 102'000'000'000 + kOffsetNs);
}

// Localizing in a saved map: before the relocalization only the odom frame is published
// (odom → base_link with every pose, the odom-frame odometry; REP 105's odom needs no map);
// the map-frame pose, odometry and map → odom start with the first (jumping) correction.
TEST(PublisherThread, BeforeTheFirstLocalizationOnlyTheOdomFrameIsPublished) {
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 16);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 16);
  SpscQueue<MapCorrection> corrections("corrections", "test", "publisher", 4);
  Doorbell bell;
  PublisherThread publisher(nullptr, OutputFrames{},
                            PublisherQueues{&poses, &odometry, &bell, &corrections}, {}, nullptr);
  publisher.HoldUntilLocalized();
  auto feed = [&](int64_t t0_ns) {
    for (int i = 0; i < 4; ++i) {
      ImuRatePose p;
      p.state.t_ns = t0_ns + i * 10'000'000;
      ASSERT_TRUE(poses.Push(p));
    }
    SweepEstimate e;
    e.status = estimator::OdometryStatus::kTracking;
    e.state.t_ns = t0_ns;
    ASSERT_TRUE(odometry.Push(e));
  };
  feed(1'000'000'000);
  const std::atomic<bool> stop{true};
  publisher.Run(stop, Watchdog::Handle{});
  PublisherCounters c = publisher.counters();
  EXPECT_EQ(c.poses, 0u);
  EXPECT_EQ(c.odometry, 0u);
  EXPECT_EQ(c.held, 5u);
  EXPECT_EQ(c.odom_odometry, 1u);
  EXPECT_EQ(c.transforms, 1u + 4u) << "/tf_static, then odom → base_link per pose";

  MapCorrection relocalized;
  relocalized.jump = true;
  relocalized.T_map_odom.translation() = Eigen::Vector3d(5.0, 0.0, 0.0);
  ASSERT_TRUE(corrections.Push(relocalized));
  feed(2'000'000'000);
  publisher.Run(stop, Watchdog::Handle{});
  c = publisher.counters();
  EXPECT_EQ(c.poses, 4u);
  EXPECT_EQ(c.odometry, 1u);
  EXPECT_EQ(c.held, 5u);
  EXPECT_EQ(c.odom_odometry, 2u);
  // A second /tf_static (this Run), a /tf per pose (map → odom riding with the first).
  EXPECT_EQ(c.transforms, 5u + 1u + 4u);
}

}  // namespace
}  // namespace swlio::daemon

// The publisher thread's REP 105 outputs, read back over DDS on loopback (domain 158): a drive
// with a non-trivial base frame and a loop correction arriving half-way. A ROS 2 consumer's view:
// map → odom (the latest at or before a pose's stamp) ∘ odom → base_link (at the stamp) is the
// published map-frame base pose; odom → base_link is the uncorrected odometry (no jump when the
// correction comes); map → odom follows the correction as it is slewed in; /tf_static holds
// base_link → imu and base_link → lidar; the odom-frame odometry is uncorrected too.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <thread>

#include "swlio/daemon/output/publisher_thread.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/subscriber.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kPeriodNs = 10'000'000;  // 100 Hz poses
constexpr int kPoses = 400;
constexpr int kCorrectionAt = 150;  // poses before the loop correction arrives

Eigen::Isometry3d Pose(const Eigen::Vector3d& p, double yaw_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
  T.translation() = p;
  return T;
}

Eigen::Isometry3d FromMsg(const std::array<double, 3>& p, const std::array<double, 4>& q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return T;
}

Eigen::Isometry3d FromMsg(const ipc::TransformStamped& t) {
  return FromMsg(t.transform.translation_m, t.transform.rotation_xyzw);
}

double AngleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

/// The IMU's (odom-frame) state of pose i: a left curve at 1 m/s.
State DriveState(int i) {
  const double t = static_cast<double>(i + 1) * 0.01;
  State s;
  s.t_ns = (i + 1) * kPeriodNs;
  s.T_world_imu = Pose({10.0 * std::sin(0.1 * t), 10.0 * (1.0 - std::cos(0.1 * t)), 0.5}, 0.1 * t);
  s.vel_world = Eigen::Vector3d(std::cos(0.1 * t), std::sin(0.1 * t), 0.0);
  return s;
}

template <typename Take>
auto CollectUntil(ipc::Subscriber& subscriber, size_t count, Take take) {
  decltype(take()) all;
  for (int i = 0; i < 500 && all.size() < count; ++i) {
    subscriber.Wait(10'000'000);
    for (auto& r : take()) all.push_back(std::move(r));
  }
  return all;
}

TEST(PublisherThreadTf, TfChainEqualsThePublishedPoseAndOdomNeverJumps) {
  ipc::IpcConfig ipc;
  ipc.domain_id = 158;
  ipc.dds_config_file = (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string();
  std::string error;
  auto participant = ipc::Participant::Create(ipc, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = ipc::Publisher::Create(*participant, ipc, &error);
  ASSERT_NE(publisher, nullptr) << error;
  ipc::SubscriberOptions options;
  options.history_depth = 10'000;
  auto subscriber = ipc::Subscriber::Create(*participant, ipc, options, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  for (const ipc::Topic t :
       {ipc::Topic::kPose, ipc::Topic::kTf, ipc::Topic::kTfStatic, ipc::Topic::kOdomOdometry}) {
    for (int i = 0; i < 1500 && publisher->MatchedSubscriptions(t) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_GT(publisher->MatchedSubscriptions(t), 0) << ipc::TopicLabel(t);
  }

  OutputFrames frames;
  frames.T_imu_base = Pose({-0.4, 0.1, -0.6}, 0.3);
  frames.T_imu_lidar = Pose({0.2, 0.0, 0.15}, -0.05);
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 1024);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 64);
  SpscQueue<MapCorrection> corrections("corrections", "test", "publisher", 4);
  Doorbell bell;
  PublisherThread thread(publisher.get(), frames,
                         PublisherQueues{&poses, &odometry, &bell, &corrections}, {}, nullptr,
                         1'000'000'000, 100, {.max_rate_mps = 0.2, .max_rate_radps = 0.05});
  thread.SetMapOdomPeriod(100'000'000);
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });
  // Each sweep's odometry (every 10th pose's state) goes in after the poses up to it were
  // published, as in the daemon, where the IMU-rate poses run ahead of the sweep ends.
  auto push = [&](int from, int to) {
    for (int i = from; i < to; ++i) {
      ImuRatePose p;
      p.state = DriveState(i);
      p.gyro_imu_radps = Eigen::Vector3d(0.0, 0.0, 0.1);
      ASSERT_TRUE(poses.Push(p));
    }
    bell.Ring();
    for (int k = 0; k < 1000 && thread.counters().poses < static_cast<uint64_t>(to); ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    for (int i = from; i < to; ++i) {
      if (i % 10 != 9) continue;
      SweepEstimate e;
      e.status = estimator::OdometryStatus::kTracking;
      e.state = DriveState(i);
      ASSERT_TRUE(odometry.Push(e));
    }
    bell.Ring();
    for (int k = 0; k < 1000 && thread.counters().odom_odometry < static_cast<uint64_t>(to / 10);
         ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  };
  push(0, kCorrectionAt);
  MapCorrection loop;  // 0.36 m and 1.1°: ~1.8 s of slewing at 0.2 m/s
  loop.T_map_odom = Pose({0.3, -0.2, 0.0}, 0.02);
  ASSERT_TRUE(corrections.Push(loop));
  bell.Ring();  // the thread takes it before the poses after it
  for (int k = 0; k < 1000 && corrections.Counters().depth > 0; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(corrections.Counters().depth, 0u);
  push(kCorrectionAt, kPoses);
  stop = true;
  runner.join();
  const PublisherCounters c = thread.counters();
  ASSERT_EQ(c.poses, static_cast<uint64_t>(kPoses));
  EXPECT_EQ(c.failures, 0u);

  const auto got_poses = CollectUntil(*subscriber, kPoses, [&] { return subscriber->TakePoses(); });
  ASSERT_EQ(got_poses.size(), static_cast<size_t>(kPoses));
  std::map<int64_t, Eigen::Isometry3d> odom_base, map_odom;  // by stamp
  size_t tf_samples = 0;
  for (int i = 0; i < 500 && odom_base.size() < static_cast<size_t>(kPoses); ++i) {
    subscriber->Wait(10'000'000);
    for (const auto& r : subscriber->TakeTf()) {
      ++tf_samples;
      for (const ipc::TransformStamped& t : r.msg.transforms) {
        if (t.frame_id == "odom" && t.child_frame_id == "base_link") {
          odom_base[t.t_ns] = FromMsg(t);
        } else if (t.frame_id == "map" && t.child_frame_id == "odom") {
          map_odom[t.t_ns] = FromMsg(t);
        } else {
          ADD_FAILURE() << "unexpected transform " << t.frame_id << " -> " << t.child_frame_id;
        }
      }
    }
  }
  ASSERT_EQ(odom_base.size(), static_cast<size_t>(kPoses));
  EXPECT_EQ(tf_samples, static_cast<size_t>(kPoses)) << "one per pose, map → odom riding along";

  // The chain at every pose's stamp, and odom → base_link is the uncorrected base pose.
  double worst_m = 0.0, worst_deg = 0.0, worst_odom_m = 0.0;
  for (int i = 0; i < kPoses; ++i) {
    const ipc::PoseWithCovarianceStamped& m = got_poses[static_cast<size_t>(i)].msg;
    ASSERT_EQ(m.frame_id, "map");
    const Eigen::Isometry3d T_map_base = FromMsg(m.pose.position_m, m.pose.orientation_xyzw);
    ASSERT_TRUE(odom_base.count(m.t_ns)) << i;
    auto at = map_odom.upper_bound(m.t_ns);  // the latest map → odom at or before the stamp
    ASSERT_NE(at, map_odom.begin()) << "no map → odom before pose " << i;
    const Eigen::Isometry3d chain = std::prev(at)->second * odom_base.at(m.t_ns);
    worst_m = std::max(worst_m, (chain.translation() - T_map_base.translation()).norm());
    worst_deg = std::max(worst_deg, AngleDeg(chain, T_map_base));
    const Eigen::Isometry3d want = DriveState(i).T_world_imu * frames.T_imu_base;
    worst_odom_m =
        std::max(worst_odom_m, (odom_base.at(m.t_ns).translation() - want.translation()).norm());
  }
  EXPECT_LT(worst_m, 0.001);
  EXPECT_LT(worst_deg, 0.01);
  EXPECT_LT(worst_odom_m, 1e-9) << "odom → base_link is the estimator's own base pose";

  // odom → base_link moves by one period's motion everywhere, also across the correction (the
  // base, 0.41 m behind and beside the IMU, at 0.99 m/s: 9.9 mm); the map-frame pose moves more
  // while the correction is slewed in (up to 0.2 m/s more).
  double odom_step_max = 0.0, map_step_max = 0.0;
  for (int i = 1; i < kPoses; ++i) {
    const auto& a = got_poses[static_cast<size_t>(i - 1)].msg;
    const auto& b = got_poses[static_cast<size_t>(i)].msg;
    odom_step_max =
        std::max(odom_step_max,
                 (odom_base.at(b.t_ns).translation() - odom_base.at(a.t_ns).translation()).norm());
    const Eigen::Vector3d pa(a.pose.position_m[0], a.pose.position_m[1], a.pose.position_m[2]);
    const Eigen::Vector3d pb(b.pose.position_m[0], b.pose.position_m[1], b.pose.position_m[2]);
    map_step_max = std::max(map_step_max, (pb - pa).norm());
  }
  EXPECT_LT(odom_step_max, 0.0100);
  EXPECT_GT(map_step_max, 0.0105) << "the map-frame pose did not take the correction";
  EXPECT_LT(map_step_max, 0.0100 + 0.2 * 0.01 + 1e-4);
  std::printf(
      "odom -> base_link step max %.2f mm, map-frame pose step max %.2f mm; chain error "
      "%.2e m, %.2e deg; %zu map -> odom samples, %zu tf samples\n",
      odom_step_max * 1e3, map_step_max * 1e3, worst_m, worst_deg, map_odom.size(), tf_samples);
  // At the end the correction is in: the map-frame pose is the correction times the odom one.
  const auto& last = got_poses.back().msg;
  const Eigen::Isometry3d T_map_base_last =
      FromMsg(last.pose.position_m, last.pose.orientation_xyzw);
  EXPECT_LT(
      (T_map_base_last.translation() - (loop.T_map_odom * odom_base.at(last.t_ns)).translation())
          .norm(),
      1e-9);

  // map → odom: identity before the loop, then one value per pose while slewing, settled on
  // the correction; never more than the period apart.
  const int64_t t_loop = got_poses[kCorrectionAt].msg.t_ns;
  size_t changes = 0;
  const Eigen::Isometry3d* previous = nullptr;
  int64_t previous_t = 0;
  for (const auto& [t, T] : map_odom) {
    if (t < t_loop) {
      EXPECT_TRUE(T.isApprox(Eigen::Isometry3d::Identity(), 1e-12)) << t;
    }
    if (previous != nullptr) {
      changes += T.isApprox(*previous, 1e-12) ? 0 : 1;
      EXPECT_LE(t - previous_t, 100'000'000 + kPeriodNs);
    }
    previous = &T;
    previous_t = t;
  }
  EXPECT_GT(changes, 100u) << "map → odom is sent as the correction is slewed in";
  EXPECT_LT((map_odom.rbegin()->second.matrix() - loop.T_map_odom.matrix()).norm(), 1e-9);

  // /tf_static: base_link → imu_link and → lidar_link.
  const auto statics = CollectUntil(*subscriber, 1, [&] { return subscriber->TakeTfStatic(); });
  ASSERT_EQ(statics.size(), 1u);
  ASSERT_EQ(statics[0].msg.transforms.size(), 2u);
  const ipc::TransformStamped& imu = statics[0].msg.transforms[0];
  const ipc::TransformStamped& lidar = statics[0].msg.transforms[1];
  EXPECT_EQ(imu.frame_id, "base_link");
  EXPECT_EQ(imu.child_frame_id, "imu_link");
  EXPECT_EQ(lidar.child_frame_id, "lidar_link");
  EXPECT_TRUE(FromMsg(imu).isApprox(frames.T_imu_base.inverse(), 1e-12));
  EXPECT_TRUE(FromMsg(lidar).isApprox(frames.T_imu_base.inverse() * frames.T_imu_lidar, 1e-12));

  // The odom-frame odometry: every sweep, uncorrected, twist in base_link.
  const auto odom =
      CollectUntil(*subscriber, kPoses / 10, [&] { return subscriber->TakeOdomOdometry(); });
  ASSERT_EQ(odom.size(), static_cast<size_t>(kPoses / 10));
  for (size_t k = 0; k < odom.size(); ++k) {
    const ipc::Odometry& o = odom[k].msg;
    EXPECT_EQ(o.frame_id, "odom");
    EXPECT_EQ(o.child_frame_id, "base_link");
    const Eigen::Isometry3d want =
        DriveState(static_cast<int>(10 * k + 9)).T_world_imu * frames.T_imu_base;
    EXPECT_LT(
        (FromMsg(o.pose.position_m, o.pose.orientation_xyzw).translation() - want.translation())
            .norm(),
        1e-9)
        << k;
  }
}

// /tf_static follows the extrinsic the estimator uses (online refinement): a sweep whose
// extrinsic moved by 1 cm re-sends base_link → lidar_link; one equal to what was sent does not.
// DDS domain 160.
TEST(PublisherThreadTf, TfStaticFollowsAnExtrinsicRefinedOnline) {
  ipc::IpcConfig ipc;
  ipc.domain_id = 160;
  ipc.dds_config_file = (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string();
  std::string error;
  auto participant = ipc::Participant::Create(ipc, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = ipc::Publisher::Create(*participant, ipc, &error);
  ASSERT_NE(publisher, nullptr) << error;
  ipc::SubscriberOptions options;
  options.topics.fill(false);
  options.topics[static_cast<size_t>(ipc::Topic::kTfStatic)] = true;
  auto subscriber = ipc::Subscriber::Create(*participant, ipc, options, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  for (int i = 0; i < 1500 && publisher->MatchedSubscriptions(ipc::Topic::kTfStatic) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));

  OutputFrames frames;
  frames.T_imu_base = Pose({-0.4, 0.1, -0.6}, 0.3);
  frames.T_imu_lidar = Pose({0.2, 0.0, 0.15}, -0.05);
  SpscQueue<ImuRatePose> poses("poses", "test", "publisher", 16);
  SpscQueue<SweepEstimate> odometry("odometry", "test", "publisher", 16);
  Doorbell bell;
  PublisherThread thread(publisher.get(), frames,
                         PublisherQueues{&poses, &odometry, &bell, nullptr}, {}, nullptr,
                         1'000'000'000, 100, {});
  std::atomic<bool> stop{false};
  std::thread runner([&] { thread.Run(stop, Watchdog::Handle{}); });
  const Eigen::Isometry3d refined = Pose({0.21, 0.0, 0.15}, -0.05);
  for (const Eigen::Isometry3d& T : {frames.T_imu_lidar, refined, refined}) {
    SweepEstimate e;
    e.status = estimator::OdometryStatus::kTracking;
    e.state = DriveState(0);
    e.T_imu_lidar = T;
    e.has_extrinsic = true;
    ASSERT_TRUE(odometry.Push(e));
    bell.Ring();
  }
  for (int k = 0; k < 1000 && thread.counters().odom_odometry < 3; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  stop = true;
  runner.join();
  EXPECT_EQ(thread.counters().static_resends, 1u);
  const auto got = CollectUntil(*subscriber, 2, [&] { return subscriber->TakeTfStatic(); });
  ASSERT_EQ(got.size(), 2u) << "the start's /tf_static and the one re-sent";
  const Eigen::Isometry3d expected = frames.T_imu_base.inverse() * refined;
  bool found = false;
  for (const ipc::TransformStamped& t : got.back().msg.transforms) {
    if (t.child_frame_id != "lidar_link") continue;
    found = true;
    EXPECT_NEAR(t.transform.translation_m[0], expected.translation().x(), 1e-12);
    EXPECT_NEAR(t.transform.translation_m[1], expected.translation().y(), 1e-12);
    EXPECT_NEAR(t.transform.translation_m[2], expected.translation().z(), 1e-12);
  }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace swlio::daemon

// Round trip of every swlio message through Cyclone DDS on loopback: Publisher → Subscriber in
// one process, values compared bit for bit. Each test has its own domain id (111..119, 126,
// 127).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ipc_test_util.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/publisher.h"
#include "swlio/ipc/subscriber.h"

namespace swlio::ipc {
namespace {

using test_util::Awkward;
using test_util::LoopbackConfig;
using test_util::SameBits;
using test_util::SamePose;
using test_util::WaitFor;

/// One participant with a publisher and a subscriber, matched on `topic`.
struct Loop {
  explicit Loop(int64_t domain, Topic topic) : config(LoopbackConfig(domain)) {
    std::string error;
    participant = Participant::Create(config, &error);
    EXPECT_NE(participant, nullptr) << error;
    if (participant == nullptr) return;
    publisher = Publisher::Create(*participant, config, &error);
    EXPECT_NE(publisher, nullptr) << error;
    subscriber = Subscriber::Create(*participant, config, SubscriberOptions{}, &error);
    EXPECT_NE(subscriber, nullptr) << error;
    if (publisher == nullptr || subscriber == nullptr) return;
    matched = WaitFor([&] { return publisher->MatchedSubscriptions(topic) > 0; });
  }
  IpcConfig config;
  std::unique_ptr<Participant> participant;
  std::unique_ptr<Publisher> publisher;
  std::unique_ptr<Subscriber> subscriber;
  bool matched = false;
};

/// Takes from `take` until `count` samples arrived or 10 s passed.
template <typename Take>
auto Collect(Subscriber& subscriber, size_t count, Take take) {
  decltype(take()) all;
  WaitFor(
      [&] {
        subscriber.Wait(10'000'000);
        for (auto& r : take()) all.push_back(std::move(r));
        return all.size() >= count;
      },
      10.0);
  return all;
}

TEST(IpcRoundTrip, PoseIsBitExact) {
  Loop loop(111, Topic::kPose);
  ASSERT_TRUE(loop.matched);
  EXPECT_EQ(loop.publisher->DdsTopicName(Topic::kPose), "rt/swlio/pose");
  std::vector<PoseWithCovarianceStamped> sent;
  // Stamps around the interesting edges: negative (floor division), zero, int32 seconds max.
  const std::vector<int64_t> stamps = {-1, 0, 1'700'000'000'123'456'789, 2'147'483'647'999'999'999};
  for (size_t i = 0; i < stamps.size(); ++i) {
    sent.push_back(test_util::MakePose(static_cast<int>(i), stamps[i]));
    ASSERT_TRUE(loop.publisher->PublishPose(sent.back()));
  }
  const auto got =
      Collect(*loop.subscriber, sent.size(), [&] { return loop.subscriber->TakePoses(); });
  ASSERT_EQ(got.size(), sent.size());
  for (size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(got[i].msg.t_ns, sent[i].t_ns);
    EXPECT_EQ(got[i].msg.frame_id, sent[i].frame_id);
    EXPECT_TRUE(SamePose(got[i].msg.pose, sent[i].pose));
    EXPECT_TRUE(SameBits(got[i].msg.covariance, sent[i].covariance));
    EXPECT_GT(got[i].receive_steady_ns, 0);
    EXPECT_GE(got[i].receive_realtime_ns, got[i].source_realtime_ns);
  }
  EXPECT_EQ(loop.publisher->published(), sent.size());
  EXPECT_EQ(loop.publisher->failures(), 0u);
}

TEST(IpcRoundTrip, StampOutsideInt32SecondsIsRefusedAndCounted) {
  Loop loop(112, Topic::kPose);
  ASSERT_NE(loop.publisher, nullptr);
  EXPECT_FALSE(loop.publisher->PublishPose(test_util::MakePose(0, 2'147'483'648'000'000'000)));
  EXPECT_FALSE(loop.publisher->PublishPose(test_util::MakePose(0, -2'147'483'649'000'000'000)));
  EXPECT_EQ(loop.publisher->failures(), 2u);
  EXPECT_EQ(loop.publisher->published(), 0u);
}

TEST(IpcRoundTrip, OdometryIsBitExact) {
  Loop loop(113, Topic::kOdometry);
  ASSERT_TRUE(loop.matched);
  Odometry sent;
  sent.t_ns = 1'234'567'890'987'654'321;
  sent.frame_id = "odom";
  sent.child_frame_id = "imu_link";
  sent.pose = test_util::MakePose(3, 0).pose;
  sent.twist.linear_mps = {Awkward(1), -2.5, Awkward(2)};
  sent.twist.angular_radps = {Awkward(5), Awkward(6), 1e-300};
  for (size_t i = 0; i < 36; ++i) {
    sent.pose_covariance[i] = Awkward(static_cast<int>(i));
    sent.twist_covariance[i] = -Awkward(static_cast<int>(i) + 3);
  }
  ASSERT_TRUE(loop.publisher->PublishOdometry(sent));
  const auto got = Collect(*loop.subscriber, 1, [&] { return loop.subscriber->TakeOdometry(); });
  ASSERT_EQ(got.size(), 1u);
  const Odometry& o = got[0].msg;
  EXPECT_EQ(o.t_ns, sent.t_ns);
  EXPECT_EQ(o.frame_id, sent.frame_id);
  EXPECT_EQ(o.child_frame_id, sent.child_frame_id);
  EXPECT_TRUE(SamePose(o.pose, sent.pose));
  EXPECT_TRUE(SameBits(o.pose_covariance, sent.pose_covariance));
  EXPECT_TRUE(SameBits(o.twist.linear_mps, sent.twist.linear_mps));
  EXPECT_TRUE(SameBits(o.twist.angular_radps, sent.twist.angular_radps));
  EXPECT_TRUE(SameBits(o.twist_covariance, sent.twist_covariance));
}

TEST(IpcRoundTrip, HealthIsExact) {
  Loop loop(114, Topic::kHealth);
  ASSERT_TRUE(loop.matched);
  DiagnosticArray sent;
  sent.t_ns = 42'000'000'001;
  sent.status.push_back({DiagnosticLevel::kOk,
                         "swlio: imu",
                         "streaming",
                         "MTi-G-710 0123",
                         {{"rate_hz", "400"}, {"crc_errors", "0"}}});
  sent.status.push_back({DiagnosticLevel::kError, "swlio: lidar", "no packets for 2.0 s", "", {}});
  sent.status.push_back(
      {static_cast<DiagnosticLevel>(7), "", "ünïcode ✓", "hw", {{"", ""}, {"k", "v\nw"}}});
  ASSERT_TRUE(loop.publisher->PublishHealth(sent));
  const auto got = Collect(*loop.subscriber, 1, [&] { return loop.subscriber->TakeHealth(); });
  ASSERT_EQ(got.size(), 1u);
  const DiagnosticArray& d = got[0].msg;
  EXPECT_EQ(d.t_ns, sent.t_ns);
  EXPECT_EQ(d.frame_id, "");
  ASSERT_EQ(d.status.size(), sent.status.size());
  for (size_t i = 0; i < sent.status.size(); ++i) {
    EXPECT_EQ(d.status[i].level, sent.status[i].level);
    EXPECT_EQ(d.status[i].name, sent.status[i].name);
    EXPECT_EQ(d.status[i].message, sent.status[i].message);
    EXPECT_EQ(d.status[i].hardware_id, sent.status[i].hardware_id);
    ASSERT_EQ(d.status[i].values.size(), sent.status[i].values.size());
    for (size_t j = 0; j < sent.status[i].values.size(); ++j) {
      EXPECT_EQ(d.status[i].values[j].key, sent.status[i].values[j].key);
      EXPECT_EQ(d.status[i].values[j].value, sent.status[i].values[j].value);
    }
  }
}

Path MakePath(size_t n) {
  Path path;
  path.t_ns = 5'000'000'000;
  path.frame_id = "map";
  for (size_t i = 0; i < n; ++i) {
    const auto pose = test_util::MakePose(static_cast<int>(i), 0).pose;
    path.poses.push_back({static_cast<int64_t>(i) * 100'000'000 - 1, i % 2 ? "map" : "", pose});
  }
  return path;
}

void ExpectSamePath(const Path& a, const Path& b) {
  EXPECT_EQ(a.t_ns, b.t_ns);
  EXPECT_EQ(a.frame_id, b.frame_id);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].t_ns, b.poses[i].t_ns) << i;
    EXPECT_EQ(a.poses[i].frame_id, b.poses[i].frame_id) << i;
    EXPECT_TRUE(SamePose(a.poses[i].pose, b.poses[i].pose)) << i;
  }
}

TEST(IpcRoundTrip, PathIsBitExactIncludingEmpty) {
  Loop loop(115, Topic::kPath);
  ASSERT_TRUE(loop.matched);
  const Path empty = MakePath(0);
  const Path long_path = MakePath(1000);
  ASSERT_TRUE(loop.publisher->PublishPath(empty));
  ASSERT_TRUE(loop.publisher->PublishPath(long_path));
  const auto got = Collect(*loop.subscriber, 2, [&] { return loop.subscriber->TakePaths(); });
  ASSERT_EQ(got.size(), 2u);
  ExpectSamePath(got[0].msg, empty);
  ExpectSamePath(got[1].msg, long_path);
}

TEST(IpcRoundTrip, LateSubscriberGetsTheLastPath) {
  // The path writer is TRANSIENT_LOCAL (KEEP_LAST 1): a subscriber that joins after the
  // publication still receives the newest path, and only that one.
  const IpcConfig config = LoopbackConfig(116);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  ASSERT_TRUE(publisher->PublishPath(MakePath(3)));
  const Path newest = MakePath(5);
  ASSERT_TRUE(publisher->PublishPath(newest));
  auto subscriber = Subscriber::Create(*participant, config, SubscriberOptions{}, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  const auto got = Collect(*subscriber, 1, [&] { return subscriber->TakePaths(); });
  ASSERT_EQ(got.size(), 1u);
  ExpectSamePath(got[0].msg, newest);
  // A volatile topic gives a late subscriber nothing from before it joined.
  EXPECT_TRUE(subscriber->TakePoses().empty());
}

TEST(IpcRoundTrip, SubscriberReadsOnlyTheTopicsItAskedFor) {
  const IpcConfig config = LoopbackConfig(117);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  SubscriberOptions options;
  options.topics = {true, false, false, false};
  auto subscriber = Subscriber::Create(*participant, config, options, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  EXPECT_TRUE(WaitFor([&] { return subscriber->MatchedPublications(Topic::kPose) > 0; }));
  EXPECT_EQ(publisher->MatchedSubscriptions(Topic::kOdometry), 0);
  EXPECT_EQ(subscriber->MatchedPublications(Topic::kOdometry), 0);
  EXPECT_TRUE(subscriber->TakeOdometry().empty());
}

TEST(IpcRoundTrip, CustomTopicNamesGetTheRosPrefix) {
  IpcConfig config = LoopbackConfig(118);
  config.pose_topic = "robot1/swlio/pose";
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  EXPECT_EQ(publisher->DdsTopicName(Topic::kPose), "rt/robot1/swlio/pose");
  EXPECT_EQ(publisher->DdsTopicName(Topic::kHealth), "rt/diagnostics");

  config.pose_topic = "/absolute";
  EXPECT_EQ(Publisher::Create(*participant, config, &error), nullptr);
  EXPECT_NE(error.find("pose_topic"), std::string::npos) << error;
}

/// A TFMessage of `n` transforms, every double awkward and distinct per (seed, index).
TFMessage MakeTf(int seed, size_t n) {
  TFMessage tf;
  for (size_t i = 0; i < n; ++i) {
    const int k = seed + static_cast<int>(7 * i);
    TransformStamped t;
    t.t_ns = 1'700'000'000'000'000'000 + k;
    t.frame_id = i % 2 == 0 ? "odom" : "map";
    t.child_frame_id = i % 2 == 0 ? "base_link" : "odom";
    t.transform.translation_m = {Awkward(k), 1.0e6 + k, Awkward(k + 3)};
    t.transform.rotation_xyzw = {Awkward(k + 5), -0.5, 0.5, std::sqrt(0.5) + k};
    tf.transforms.push_back(t);
  }
  return tf;
}

void ExpectSameTf(const TFMessage& a, const TFMessage& b) {
  ASSERT_EQ(a.transforms.size(), b.transforms.size());
  for (size_t i = 0; i < a.transforms.size(); ++i) {
    const TransformStamped& x = a.transforms[i];
    const TransformStamped& y = b.transforms[i];
    EXPECT_EQ(x.t_ns, y.t_ns) << i;
    EXPECT_EQ(x.frame_id, y.frame_id) << i;
    EXPECT_EQ(x.child_frame_id, y.child_frame_id) << i;
    EXPECT_TRUE(SameBits(x.transform.translation_m, y.transform.translation_m)) << i;
    EXPECT_TRUE(SameBits(x.transform.rotation_xyzw, y.transform.rotation_xyzw)) << i;
  }
}

// /tf as tf2 reads it: DDS topic "rt/tf", type tf2_msgs::msg::dds_::TFMessage_; messages of 0,
// 1, 2 and 9 transforms (more than the writer's inline storage) arrive bit for bit, in order.
TEST(IpcRoundTrip, TfIsBitExact) {
  Loop loop(126, Topic::kTf);
  ASSERT_TRUE(loop.matched);
  EXPECT_EQ(loop.publisher->DdsTopicName(Topic::kTf), "rt/tf");
  EXPECT_EQ(loop.publisher->DdsTopicName(Topic::kTfStatic), "rt/tf_static");
  std::vector<TFMessage> sent = {MakeTf(1, 1), MakeTf(2, 2), MakeTf(3, 0), MakeTf(4, 9)};
  for (const TFMessage& tf : sent) ASSERT_TRUE(loop.publisher->PublishTf(tf));
  const auto got =
      Collect(*loop.subscriber, sent.size(), [&] { return loop.subscriber->TakeTf(); });
  ASSERT_EQ(got.size(), sent.size());
  for (size_t i = 0; i < sent.size(); ++i) ExpectSameTf(got[i].msg, sent[i]);
  EXPECT_TRUE(loop.subscriber->TakeTfStatic().empty()) << "/tf samples only on /tf";
  EXPECT_EQ(loop.publisher->failures(), 0u);
  // A stamp outside builtin_interfaces/Time in any transform refuses the whole message.
  TFMessage bad = MakeTf(5, 3);
  bad.transforms[2].t_ns = 2'147'483'648'000'000'000;
  EXPECT_FALSE(loop.publisher->PublishTf(bad));
  EXPECT_EQ(loop.publisher->failures(), 1u);
}

// /tf_static is latched like tf2_ros's StaticTransformBroadcaster (TRANSIENT_LOCAL, KEEP_LAST
// 1): a listener that joins later gets the newest set of static transforms, and only it.
TEST(IpcRoundTrip, LateSubscriberGetsTheLastStaticTransforms) {
  const IpcConfig config = LoopbackConfig(127);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  ASSERT_TRUE(publisher->PublishTfStatic(MakeTf(10, 1)));
  const TFMessage newest = MakeTf(11, 2);
  ASSERT_TRUE(publisher->PublishTfStatic(newest));
  ASSERT_TRUE(publisher->PublishTf(MakeTf(12, 1)));  // volatile: not for a late joiner
  auto subscriber = Subscriber::Create(*participant, config, SubscriberOptions{}, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  const auto got = Collect(*subscriber, 1, [&] { return subscriber->TakeTfStatic(); });
  ASSERT_EQ(got.size(), 1u);
  ExpectSameTf(got[0].msg, newest);
  EXPECT_TRUE(subscriber->TakeTf().empty());
}

}  // namespace
}  // namespace swlio::ipc

// PublishPose, PublishOdometry and PublishTf of two transforms (IMU and scan rate) make no C++
// heap allocation: the message is converted into a stack C struct whose strings borrow the
// caller's. Counted with a replaced
// global operator new (this test binary only). Cyclone DDS itself is C and allocates the
// serialized sample with malloc, which this counter does not see. Domain 119.
#include <gtest/gtest.h>

#include "allocation_counter.h"

#include "ipc_test_util.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/publisher.h"
#include "swlio/ipc/subscriber.h"

namespace swlio::ipc {
namespace {

TEST(IpcPublish, PoseOdometryAndTfDoNotAllocate) {
  const IpcConfig config = test_util::LoopbackConfig(119);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  auto subscriber = Subscriber::Create(*participant, config, SubscriberOptions{}, &error);
  ASSERT_NE(subscriber, nullptr) << error;
  ASSERT_TRUE(test_util::WaitFor([&] {
    return publisher->MatchedSubscriptions(Topic::kPose) > 0 &&
           publisher->MatchedSubscriptions(Topic::kOdometry) > 0 &&
           publisher->MatchedSubscriptions(Topic::kTf) > 0;
  }));
  PoseWithCovarianceStamped pose = test_util::MakePose(1, 1'000);
  pose.frame_id = "a frame name longer than any small-string buffer";
  Odometry odometry;
  odometry.frame_id = pose.frame_id;
  odometry.child_frame_id = "another frame name longer than a small-string buffer";
  TFMessage tf;
  tf.transforms.resize(2);
  tf.transforms[0].frame_id = odometry.child_frame_id;
  tf.transforms[0].child_frame_id = pose.frame_id;
  tf.transforms[1].frame_id = pose.frame_id;
  tf.transforms[1].child_frame_id = odometry.child_frame_id;

  const int64_t before = test::HeapAllocations();
  ASSERT_GT(before, 0);  // the counter sees the set-up's allocations
  for (int i = 0; i < 100; ++i) {
    pose.t_ns += 2'500'000;
    odometry.t_ns = pose.t_ns;
    ASSERT_TRUE(publisher->PublishPose(pose));
    ASSERT_TRUE(publisher->PublishOdometry(odometry));
    for (TransformStamped& t : tf.transforms) t.t_ns = pose.t_ns;
    ASSERT_TRUE(publisher->PublishTf(tf));
  }
  EXPECT_EQ(test::HeapAllocations() - before, 0);
  // The samples did go out: the subscriber (which allocates, after counting) takes them.
  EXPECT_TRUE(test_util::WaitFor([&] { return subscriber->TakePoses().size() > 0; }));
  EXPECT_TRUE(test_util::WaitFor([&] { return subscriber->TakeTf().size() > 0; }));
}

}  // namespace
}  // namespace swlio::ipc

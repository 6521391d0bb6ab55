#include "tf_check_mode.h"

#include <time.h>

#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

#include "fastdds_reader.h"
#include "geometry_msgsPubSubTypes.h"
#include "tf2_msgsPubSubTypes.h"

namespace swlio::tools::fastdds_echo {
namespace {

namespace fdds = eprosima::fastdds::dds;
namespace gm = geometry_msgs::msg::dds_;
using TFMessage = tf2_msgs::msg::dds_::TFMessage_;

/// The receiver's ROS time: CLOCK_REALTIME, ns.
int64_t RealtimeNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

int64_t StampNs(const std_msgs::msg::dds_::Header_& h) {
  return static_cast<int64_t>(h.stamp().sec()) * 1'000'000'000 + h.stamp().nanosec();
}

Eigen::Isometry3d ToIsometry(double x, double y, double z, const gm::Quaternion_& q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

Eigen::Isometry3d ToIsometry(const gm::Transform_& t) {
  return ToIsometry(t.translation().x(), t.translation().y(), t.translation().z(), t.rotation());
}

void Print(const std::string& line) {
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace

int RunTfCheck(fdds::DomainParticipant* participant, const TfCheckOptions& options) {
  TfCheck check(options.frames, Print);
  fdds::Subscriber* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  std::vector<Reader> readers;
  std::string ready = "ready";
  auto on_tf = [&check](const TFMessage& m) {
    const int64_t now_ns = RealtimeNowNs();
    for (const gm::TransformStamped_& t : m.transforms()) {
      check.OnTransform(StampNs(t.header()), t.header().frame_id(), t.child_frame_id(),
                        ToIsometry(t.transform()), now_ns);
    }
    check.OnTfDone();
  };
  auto on_tf_static = [&check](const TFMessage& m) {
    const int64_t now_ns = RealtimeNowNs();
    std::vector<StaticTransform> transforms;
    std::vector<int64_t> stamps_ns;
    for (const gm::TransformStamped_& t : m.transforms()) {
      transforms.push_back({t.header().frame_id(), t.child_frame_id(), ToIsometry(t.transform())});
      stamps_ns.push_back(StampNs(t.header()));
    }
    check.OnStatic(transforms, stamps_ns, now_ns);
  };
  auto on_pose = [&check](const gm::PoseWithCovarianceStamped_& m) {
    const gm::Pose_& p = m.pose().pose();
    check.OnPose(StampNs(m.header()), m.header().frame_id(),
                 ToIsometry(p.position().x(), p.position().y(), p.position().z(), p.orientation()),
                 RealtimeNowNs());
  };
  using TfType = tf2_msgs::msg::dds_::TFMessage_PubSubType;
  if (subscriber == nullptr ||
      !AddReader<TfType>(participant, subscriber, options.tf_topic, {false, 100}, on_tf, &readers,
                         &ready) ||
      !AddReader<TfType>(participant, subscriber, options.tf_static_topic, {true, 1}, on_tf_static,
                         &readers, &ready) ||
      !AddReader<gm::PoseWithCovarianceStamped_PubSubType>(
          participant, subscriber, options.pose_topic, {false, 10}, on_pose, &readers, &ready)) {
    return 1;
  }
  Print(ready);
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(options.duration_s));
  while (std::chrono::steady_clock::now() < deadline) {
    bool any = false;
    for (Reader& r : readers) {
      while (r.take()) any = true;
    }
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  check.Finish();
  return 0;
}

}  // namespace swlio::tools::fastdds_echo

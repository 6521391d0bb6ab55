#include "initialpose_writer.h"

#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <numbers>
#include <sstream>

#include "geometry_msgsPubSubTypes.h"

namespace swlio::tools::fastdds_echo {
namespace {

namespace fdds = eprosima::fastdds::dds;
namespace gm = geometry_msgs::msg::dds_;

int64_t NowNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

/// rviz2's "2D Pose Estimate" message (rviz_default_plugins' InitialPoseTool: frame = the fixed
/// frame, covariance x/y 0.25 and yaw (π/12)²).
gm::PoseWithCovarianceStamped_ Message(const InitialPoseSend& s) {
  gm::PoseWithCovarianceStamped_ m;
  const int64_t t = NowNs(CLOCK_REALTIME);
  m.header().stamp().sec(static_cast<int32_t>(t / 1'000'000'000));
  m.header().stamp().nanosec(static_cast<uint32_t>(t % 1'000'000'000));
  m.header().frame_id("map");
  m.pose().pose().position().x(s.x_m);
  m.pose().pose().position().y(s.y_m);
  const double half = s.yaw_deg * std::numbers::pi / 360.0;
  m.pose().pose().orientation().z(std::sin(half));
  m.pose().pose().orientation().w(std::cos(half));
  std::array<double, 36> covariance{};
  covariance[0] = 0.25;
  covariance[7] = 0.25;
  covariance[35] = (std::numbers::pi / 12.0) * (std::numbers::pi / 12.0);
  m.pose().covariance(covariance);
  return m;
}

}  // namespace

std::optional<InitialPoseSend> ParseInitialPose(const std::string& text) {
  InitialPoseSend s;
  char c1 = 0, c2 = 0, at = 0;
  std::istringstream in(text);
  if (!(in >> s.x_m >> c1 >> s.y_m >> c2 >> s.yaw_deg >> at >> s.after_s) || c1 != ',' ||
      c2 != ',' || at != '@' || !std::isfinite(s.x_m) || !std::isfinite(s.y_m) ||
      !std::isfinite(s.yaw_deg) || !(s.after_s >= 0.0)) {
    return std::nullopt;
  }
  std::string rest;
  if (in >> rest) return std::nullopt;
  return s;
}

std::unique_ptr<InitialPoseWriter> InitialPoseWriter::Create(fdds::DomainParticipant* participant,
                                                             const std::string& topic_name,
                                                             std::vector<InitialPoseSend> sends) {
  fdds::TypeSupport type(new gm::PoseWithCovarianceStamped_PubSubType());
  if (type.register_type(participant) != ReturnCode_t::RETCODE_OK) return nullptr;
  fdds::Topic* topic =
      participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  fdds::Publisher* publisher = participant->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  if (topic == nullptr || publisher == nullptr) return nullptr;
  fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
  qos.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
  qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = 10;
  fdds::DataWriter* writer = publisher->create_datawriter(topic, qos);
  if (writer == nullptr) return nullptr;
  std::unique_ptr<InitialPoseWriter> w(new InitialPoseWriter());
  const int64_t start_ns = NowNs(CLOCK_MONOTONIC);
  w->thread_ = std::thread([writer, start_ns, sends = std::move(sends)] {
    for (const InitialPoseSend& s : sends) {
      const int64_t at_ns = start_ns + static_cast<int64_t>(s.after_s * 1e9);
      fdds::PublicationMatchedStatus matched;
      while (NowNs(CLOCK_MONOTONIC) < at_ns ||
             (writer->get_publication_matched_status(matched) == ReturnCode_t::RETCODE_OK &&
              matched.current_count == 0 && NowNs(CLOCK_MONOTONIC) < at_ns + 10'000'000'000)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      gm::PoseWithCovarianceStamped_ m = Message(s);
      const int64_t sent_ns = NowNs(CLOCK_MONOTONIC);
      const bool ok = writer->write(&m);
      std::printf("initialpose x=%.6f y=%.6f yaw_deg=%.6f sent_mono_ns=%lld written=%d\n", s.x_m,
                  s.y_m, s.yaw_deg, static_cast<long long>(sent_ns), ok ? 1 : 0);
      std::fflush(stdout);
    }
  });
  return w;
}

InitialPoseWriter::~InitialPoseWriter() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace swlio::tools::fastdds_echo

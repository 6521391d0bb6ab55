// swlio-fastdds-echo: receives swlio's topics with Fast DDS, the default middleware of ROS 2,
// as a ROS 2 node would (reader QoS RELIABLE, VOLATILE, KEEP_LAST 10 — ROS 2's default
// subscription; the map cloud TRANSIENT_LOCAL, KEEP_LAST 1, as a map display asks), and prints
// every sample in a bit-exact text form (fastdds_print.h) so that a test can compare it bit for bit
// with what the Cyclone DDS publisher wrote.
//
// Output: "ready" followed by "<topic>=<type name>" for each reader, then one line per sample.
// With --tf-check it reads /tf, /tf_static and the pose instead, as a ROS 2 node with a tf2
// listener does, and prints per pose how far the TF chain is from it (tf_check.h).
//
// Loopback only: the participant comes from --profile (set as FASTRTPS_DEFAULT_PROFILES_FILE
// and loaded before the default QoS is read, otherwise Fast DDS silently keeps its defaults),
// and the program refuses to start unless that QoS uses no builtin transport, only UDPv4
// transports whitelisted to 127.0.0.1, and only 127.0.0.1 locators.
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <CLI/CLI.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "diagnostic_msgsPubSubTypes.h"
#include "fastdds_print.h"
#include "fastdds_reader.h"
#include "geometry_msgsPubSubTypes.h"
#include "initialpose_writer.h"
#include "nav_msgsPubSubTypes.h"
#include "sensor_msgsPubSubTypes.h"
#include "tf_check_mode.h"

#if defined(__SANITIZE_ADDRESS__)
#define SWLIO_FASTDDS_ECHO_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SWLIO_FASTDDS_ECHO_ASAN 1
#endif
#endif
#ifdef SWLIO_FASTDDS_ECHO_ASAN
// Sanitizer builds only. Debian's Fast DDS 2.9.1 allocates a StatisticsReaderImpl (64 bytes)
// and deletes it through RTPSReader's sized delete (56 bytes) when a DataReader is destroyed.
// ASan reports new-delete-type-mismatch for this defect inside the library. Nothing of ours is
// involved, so that one check is off in this program.
extern "C" __attribute__((used)) const char* __asan_default_options() {
  return "new_delete_type_mismatch=0";
}
#endif

namespace {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;
using eprosima::fastrtps::rtps::LocatorList_t;
using swlio::tools::fastdds_echo::AddReader;
using swlio::tools::fastdds_echo::Reader;
using swlio::tools::fastdds_echo::ReaderQos;

bool AllLoopback(const LocatorList_t& list, const char* what, std::string* why) {
  for (const Locator_t& locator : list) {
    if (locator.kind != LOCATOR_KIND_UDPv4 || IPLocator::toIPv4string(locator) != "127.0.0.1") {
      *why = std::string(what) + " has a locator that is not UDPv4 127.0.0.1";
      return false;
    }
  }
  return true;
}

/// The guard of dds-notes.md: no builtin transports, user transports present and each a UDPv4
/// transport whitelisted to exactly 127.0.0.1, every unicast locator 127.0.0.1, no multicast.
bool IsLoopbackOnly(const fdds::DomainParticipantQos& qos, std::string* why) {
  const auto& transport = qos.transport();
  if (transport.use_builtin_transports) {
    *why = "builtin transports are in use (UDP on every interface, shared memory)";
    return false;
  }
  if (transport.user_transports.empty()) {
    *why = "no user transport is configured";
    return false;
  }
  for (const auto& descriptor : transport.user_transports) {
    const auto udp =
        std::dynamic_pointer_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor>(descriptor);
    if (udp == nullptr || udp->interfaceWhiteList.empty()) {
      *why = "a user transport is not UDPv4 with an interfaceWhiteList";
      return false;
    }
    for (const std::string& address : udp->interfaceWhiteList) {
      if (address != "127.0.0.1") {
        *why = "interfaceWhiteList contains " + address;
        return false;
      }
    }
  }
  const auto& builtin = qos.wire_protocol().builtin;
  if (!builtin.metatrafficMulticastLocatorList.empty() ||
      !qos.wire_protocol().default_multicast_locator_list.empty()) {
    *why = "a multicast locator is configured";
    return false;
  }
  return AllLoopback(builtin.initialPeersList, "initialPeersList", why) &&
         AllLoopback(builtin.metatrafficUnicastLocatorList, "metatrafficUnicastLocatorList", why) &&
         AllLoopback(qos.wire_protocol().default_unicast_locator_list, "defaultUnicastLocatorList",
                     why) &&
         !builtin.initialPeersList.empty();
}

struct Options {
  std::string profile;
  uint32_t domain = 0;
  std::string pose_topic = "rt/swlio/pose";
  std::string odometry_topic = "rt/swlio/odometry";
  std::string health_topic = "rt/diagnostics";
  std::string path_topic = "rt/swlio/path";
  std::string map_topic = "rt/swlio/map";
  int count = 0;
  double timeout_s = 30.0;
  bool tf_check = false;
  swlio::tools::fastdds_echo::TfCheckOptions tf;
  std::vector<std::string> initialposes;  ///< --initialpose X,Y,YAW_DEG@AFTER_S
  std::string initialpose_topic = "rt/initialpose";
};

/// Prints each sample of the reader in fastdds_print.h's form.
template <typename PubSubType>
bool AddPrinter(fdds::DomainParticipant* participant,
                fdds::Subscriber* subscriber,
                const std::string& topic_name,
                std::vector<Reader>* readers,
                std::string* ready,
                ReaderQos qos = {}) {
  return AddReader<PubSubType>(
      participant, subscriber, topic_name, qos,
      [](const typename PubSubType::type& m) {
        std::printf("%s\n", swlio::tools::fastdds_echo::Line(m).c_str());
        std::fflush(stdout);
      },
      readers, ready);
}

/// Receives until `count` samples or the timeout; returns the exit code.
int Receive(fdds::DomainParticipant* participant, const Options& options) {
  fdds::Subscriber* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  std::vector<Reader> readers;
  std::string ready = "ready";
  namespace gm = geometry_msgs::msg::dds_;
  if (subscriber == nullptr ||
      !AddPrinter<gm::PoseWithCovarianceStamped_PubSubType>(participant, subscriber,
                                                            options.pose_topic, &readers, &ready) ||
      !AddPrinter<nav_msgs::msg::dds_::Odometry_PubSubType>(
          participant, subscriber, options.odometry_topic, &readers, &ready) ||
      !AddPrinter<diagnostic_msgs::msg::dds_::DiagnosticArray_PubSubType>(
          participant, subscriber, options.health_topic, &readers, &ready) ||
      !AddPrinter<nav_msgs::msg::dds_::Path_PubSubType>(participant, subscriber, options.path_topic,
                                                        &readers, &ready) ||
      !AddPrinter<sensor_msgs::msg::dds_::PointCloud2_PubSubType>(
          participant, subscriber, options.map_topic, &readers, &ready, {true, 1})) {
    return 1;
  }
  std::printf("%s\n", ready.c_str());
  std::fflush(stdout);

  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(options.timeout_s));
  int received = 0;
  while (options.count <= 0 || received < options.count) {
    if (std::chrono::steady_clock::now() > deadline) return options.count > 0 ? 2 : 0;
    bool any = false;
    for (Reader& r : readers) {
      while (r.take()) {
        any = true;
        ++received;
      }
    }
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return 0;
}

}  // namespace

namespace {

int Main(int argc, char** argv) {
  CLI::App app{"Fast DDS subscriber of swlio's topics (a ROS 2 stand-in), loopback only"};
  Options options;
  app.add_option("--profile", options.profile, "Fast DDS XML profile (loopback only)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--domain", options.domain, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--pose-topic", options.pose_topic, "DDS topic (ROS 2 /swlio/pose)");
  app.add_option("--odometry-topic", options.odometry_topic, "DDS topic");
  app.add_option("--health-topic", options.health_topic, "DDS topic");
  app.add_option("--path-topic", options.path_topic, "DDS topic");
  app.add_option("--map-topic", options.map_topic, "DDS topic (latched: transient local)");
  app.add_option("--count", options.count, "exit after this many samples (0: until timeout)");
  app.add_option("--timeout", options.timeout_s, "give up after this many seconds");
  app.add_flag("--tf-check", options.tf_check,
               "as a tf2 listener: compose /tf and /tf_static at each pose's stamp and print how "
               "far that is from the pose (tf_check.h); runs until --timeout");
  app.add_option("--tf-topic", options.tf.tf_topic, "DDS topic (--tf-check)");
  app.add_option("--tf-static-topic", options.tf.tf_static_topic, "DDS topic (--tf-check)");
  app.add_option("--map-frame", options.tf.frames.map, "(--tf-check)");
  app.add_option("--odom-frame", options.tf.frames.odom, "(--tf-check)");
  app.add_option("--base-frame", options.tf.frames.base, "(--tf-check)");
  app.add_option("--initialpose", options.initialposes,
                 "X,Y,YAW_DEG@AFTER_S: publish /initialpose as rviz2's 2D Pose Estimate does, "
                 "AFTER_S seconds after start (repeatable; initialpose_writer.h)");
  app.add_option("--initialpose-topic", options.initialpose_topic, "DDS topic (--initialpose)");
  CLI11_PARSE(app, argc, argv);
  std::vector<swlio::tools::fastdds_echo::InitialPoseSend> sends;
  for (const std::string& text : options.initialposes) {
    const auto s = swlio::tools::fastdds_echo::ParseInitialPose(text);
    if (!s) {
      std::fprintf(stderr, "swlio-fastdds-echo: --initialpose %s: expected X,Y,YAW_DEG@AFTER_S\n",
                   text.c_str());
      return 64;
    }
    sends.push_back(*s);
  }
  options.tf.pose_topic = options.pose_topic;
  options.tf.duration_s = options.timeout_s;

  // The profile must be in place before the factory reads its defaults.
  setenv("FASTRTPS_DEFAULT_PROFILES_FILE", options.profile.c_str(), 1);
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  if (factory->load_profiles() != ReturnCode_t::RETCODE_OK) {
    std::fprintf(stderr, "swlio-fastdds-echo: cannot load profile %s\n", options.profile.c_str());
    return 1;
  }
  const fdds::DomainParticipantQos qos = factory->get_default_participant_qos();
  std::string why;
  if (!IsLoopbackOnly(qos, &why)) {
    std::fprintf(stderr, "swlio-fastdds-echo: refusing to start: %s: %s\n", options.profile.c_str(),
                 why.c_str());
    return 1;
  }
  fdds::DomainParticipant* participant = factory->create_participant(options.domain, qos);
  if (participant == nullptr) {
    std::fprintf(stderr, "swlio-fastdds-echo: cannot create the participant\n");
    return 1;
  }
  std::unique_ptr<swlio::tools::fastdds_echo::InitialPoseWriter> writer;
  if (!sends.empty()) {
    writer = swlio::tools::fastdds_echo::InitialPoseWriter::Create(
        participant, options.initialpose_topic, std::move(sends));
    if (!writer) {
      std::fprintf(stderr, "swlio-fastdds-echo: cannot create the /initialpose writer\n");
      return 1;
    }
  }
  const int code = options.tf_check
                       ? swlio::tools::fastdds_echo::RunTfCheck(participant, options.tf)
                       : Receive(participant, options);
  writer.reset();  // its sends are done before the entities go
  participant->delete_contained_entities();
  factory->delete_participant(participant);
  if (code == 1) std::fprintf(stderr, "swlio-fastdds-echo: cannot create the reader\n");
  if (code == 2) std::fprintf(stderr, "swlio-fastdds-echo: timeout\n");
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "swlio-fastdds-echo", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown exception\n", "swlio-fastdds-echo");
  }
  return 1;
}

// swlio-fastdds-echo: receives swlio's pose topic with Fast DDS, the default middleware of ROS 2,
// as a ROS 2 node would (reader QoS RELIABLE, VOLATILE, KEEP_LAST 10 — ROS 2's default
// subscription), and prints every sample with its doubles as IEEE-754 bit patterns so that a
// test can check them bit for bit against what the Cyclone DDS publisher wrote.
//
// Output: "ready" once the reader exists, then one line per sample:
//   pose <sec> <nanosec> <frame_id> <x y z qx qy qz qw cov[0..35] as 16 hex digits each>
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
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "geometry_msgsPubSubTypes.h"

namespace {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;
using eprosima::fastrtps::rtps::LocatorList_t;
using PoseMsg = geometry_msgs::msg::dds_::PoseWithCovarianceStamped_;
using PosePubSubType = geometry_msgs::msg::dds_::PoseWithCovarianceStamped_PubSubType;

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

void PrintBits(double v) {
  uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  std::printf(" %016" PRIx64, bits);
}

void PrintPose(const PoseMsg& m) {
  std::printf("pose %" PRId32 " %" PRIu32 " %s", m.header().stamp().sec(),
              m.header().stamp().nanosec(), m.header().frame_id().c_str());
  const auto& pose = m.pose().pose();
  for (double v :
       {pose.position().x(), pose.position().y(), pose.position().z(), pose.orientation().x(),
        pose.orientation().y(), pose.orientation().z(), pose.orientation().w()}) {
    PrintBits(v);
  }
  for (double v : m.pose().covariance()) PrintBits(v);
  std::printf("\n");
  std::fflush(stdout);
}

struct Options {
  std::string profile;
  uint32_t domain = 0;
  std::string topic = "rt/swlio/pose";
  int count = 0;
  double timeout_s = 30.0;
};

/// Receives until `count` samples or the timeout; returns the exit code.
int Receive(fdds::DomainParticipant* participant, const Options& options) {
  fdds::TypeSupport type(new PosePubSubType());
  if (type.register_type(participant) != ReturnCode_t::RETCODE_OK) return 1;
  fdds::Topic* topic =
      participant->create_topic(options.topic, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  fdds::Subscriber* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (topic == nullptr || subscriber == nullptr) return 1;
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  qos.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
  qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = 10;
  fdds::DataReader* reader = subscriber->create_datareader(topic, qos);
  if (reader == nullptr) return 1;
  std::printf("ready %s %s\n", options.topic.c_str(), type.get_type_name().c_str());
  std::fflush(stdout);

  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(options.timeout_s));
  int received = 0;
  PoseMsg sample;
  fdds::SampleInfo info;
  while (options.count <= 0 || received < options.count) {
    if (std::chrono::steady_clock::now() > deadline) return options.count > 0 ? 2 : 0;
    if (!reader->wait_for_unread_message(eprosima::fastrtps::Duration_t(0, 100'000'000))) continue;
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      PrintPose(sample);
      ++received;
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Fast DDS subscriber of swlio's pose (a ROS 2 stand-in), loopback only"};
  Options options;
  app.add_option("--profile", options.profile, "Fast DDS XML profile (loopback only)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--domain", options.domain, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--topic", options.topic, "DDS topic name (ROS 2 /swlio/pose is rt/swlio/pose)");
  app.add_option("--count", options.count, "exit after this many samples (0: until timeout)");
  app.add_option("--timeout", options.timeout_s, "give up after this many seconds");
  CLI11_PARSE(app, argc, argv);

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
  const int code = Receive(participant, options);
  participant->delete_contained_entities();
  factory->delete_participant(participant);
  if (code == 1) std::fprintf(stderr, "swlio-fastdds-echo: cannot create the reader\n");
  if (code == 2) std::fprintf(stderr, "swlio-fastdds-echo: timeout\n");
  return code;
}

#include "swlio/ipc/subscriber.h"

#include <time.h>

#include <array>

#include "wire.h"

namespace swlio::ipc {
namespace {

int64_t NowNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + static_cast<int64_t>(ts.tv_nsec);
}

}  // namespace

std::unique_ptr<Subscriber> Subscriber::Create(const Participant& participant,
                                               const IpcConfig& config,
                                               const SubscriberOptions& options,
                                               std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error != nullptr) *error = message;
    return std::unique_ptr<Subscriber>();
  };
  const ConfigIssues issues = config.Validate();
  if (!issues.empty()) {
    return fail("invalid ipc configuration: " + issues.front().key + " " + issues.front().reason);
  }
  if (options.history_depth < 1 || options.map_history_depth < 1) {
    return fail("history_depth and map_history_depth must be at least 1");
  }
  std::unique_ptr<Subscriber> subscriber(new Subscriber());
  subscriber->waitset_ = dds_create_waitset(participant.handle());
  if (subscriber->waitset_ < 0) {
    return fail(std::string("cannot create DDS waitset: ") + dds_strretcode(subscriber->waitset_));
  }
  for (int i = 0; i < kTopicCount; ++i) {
    if (!options.topics[static_cast<size_t>(i)]) continue;
    const auto topic_id = static_cast<Topic>(i);
    const std::string name = wire::DdsTopicName(config, topic_id);
    if (name.empty()) continue;  // an optional topic switched off
    const dds_entity_t topic = dds_create_topic(participant.handle(), wire::Descriptor(topic_id),
                                                name.c_str(), nullptr, nullptr);
    if (topic < 0) {
      return fail("cannot create DDS topic '" + name + "': " + dds_strretcode(topic));
    }
    subscriber->topics_[static_cast<size_t>(i)] = topic;
    const bool large = topic_id == Topic::kMap || topic_id == Topic::kSweep;  // MBs, 100s of kB
    const int depth = large ? options.map_history_depth : options.history_depth;
    dds_qos_t* qos = wire::MakeQos(topic_id, /*writer=*/false, depth);
    const dds_entity_t reader = dds_create_reader(participant.handle(), topic, qos, nullptr);
    dds_delete_qos(qos);
    if (reader < 0) {
      return fail("cannot create DDS reader for '" + name + "': " + dds_strretcode(reader));
    }
    subscriber->readers_[static_cast<size_t>(i)] = reader;
    const dds_entity_t condition = dds_create_readcondition(reader, DDS_ANY_STATE);
    if (condition < 0 || dds_waitset_attach(subscriber->waitset_, condition, reader) < 0) {
      return fail("cannot attach a read condition for '" + name + "'");
    }
  }
  return subscriber;
}

Subscriber::~Subscriber() {
  if (waitset_ > 0) dds_delete(waitset_);
  for (size_t i = 0; i < readers_.size(); ++i) {
    if (readers_[i] > 0) dds_delete(readers_[i]);  // also deletes its read condition
    if (topics_[i] > 0) dds_delete(topics_[i]);
  }
}

bool Subscriber::Wait(int64_t timeout_ns) {
  return dds_waitset_wait(waitset_, nullptr, 0, static_cast<dds_duration_t>(timeout_ns)) > 0;
}

template <typename Message, typename Wire>
std::vector<Received<Message>> Subscriber::Take(Topic topic) {
  std::vector<Received<Message>> out;
  const int32_t reader = readers_[static_cast<size_t>(topic)];
  if (reader <= 0) return out;
  constexpr size_t kBatch = 32;
  std::array<void*, kBatch> samples{};
  std::array<dds_sample_info_t, kBatch> infos{};
  for (;;) {
    samples.fill(nullptr);  // null buffers: Cyclone lends its own
    const dds_return_t n = dds_take(reader, samples.data(), infos.data(), kBatch, kBatch);
    if (n <= 0) break;
    const int64_t steady_ns = NowNs(CLOCK_MONOTONIC);
    const int64_t realtime_ns = NowNs(CLOCK_REALTIME);
    for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
      if (!infos[i].valid_data) continue;
      Received<Message> r;
      if (!wire::FromWire(*static_cast<const Wire*>(samples[i]), &r.msg)) {
        ++decode_failures_;
        continue;
      }
      r.receive_steady_ns = steady_ns;
      r.receive_realtime_ns = realtime_ns;
      r.source_realtime_ns = infos[i].source_timestamp;
      out.push_back(std::move(r));
    }
    dds_return_loan(reader, samples.data(), n);
    if (static_cast<size_t>(n) < kBatch) break;
  }
  return out;
}

std::vector<Received<PoseWithCovarianceStamped>> Subscriber::TakePoses() {
  return Take<PoseWithCovarianceStamped, wire::PoseCovStampedMsg>(Topic::kPose);
}

std::vector<Received<Odometry>> Subscriber::TakeOdometry() {
  return Take<Odometry, wire::OdometryMsg>(Topic::kOdometry);
}

std::vector<Received<DiagnosticArray>> Subscriber::TakeHealth() {
  return Take<DiagnosticArray, wire::DiagnosticArrayMsg>(Topic::kHealth);
}

std::vector<Received<Path>> Subscriber::TakePaths() {
  return Take<Path, wire::PathMsg>(Topic::kPath);
}

std::vector<Received<PointCloud2>> Subscriber::TakeMaps() {
  return Take<PointCloud2, wire::PointCloud2Msg>(Topic::kMap);
}

std::vector<Received<PointCloud2>> Subscriber::TakeSweeps() {
  return Take<PointCloud2, wire::PointCloud2Msg>(Topic::kSweep);
}

std::vector<Received<Odometry>> Subscriber::TakeOdomOdometry() {
  return Take<Odometry, wire::OdometryMsg>(Topic::kOdomOdometry);
}

std::vector<Received<TFMessage>> Subscriber::TakeTf() {
  return Take<TFMessage, wire::TFMessageMsg>(Topic::kTf);
}

std::vector<Received<TFMessage>> Subscriber::TakeTfStatic() {
  return Take<TFMessage, wire::TFMessageMsg>(Topic::kTfStatic);
}

int Subscriber::MatchedPublications(Topic topic) const {
  const int32_t reader = readers_[static_cast<size_t>(topic)];
  dds_subscription_matched_status_t status{};
  if (reader <= 0 || dds_get_subscription_matched_status(reader, &status) != DDS_RETCODE_OK) {
    return 0;
  }
  return static_cast<int>(status.current_count);
}

}  // namespace swlio::ipc

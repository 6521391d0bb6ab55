#include "swlio/ipc/publisher.h"

#include "wire.h"

namespace swlio::ipc {

const char* TopicLabel(Topic topic) {
  switch (topic) {
    case Topic::kPose:
      return "pose";
    case Topic::kOdometry:
      return "odometry";
    case Topic::kHealth:
      return "health";
    case Topic::kPath:
      return "path";
    case Topic::kMap:
      return "map";
    case Topic::kOdomOdometry:
      return "odom_odometry";
    case Topic::kTf:
      return "tf";
    case Topic::kTfStatic:
      return "tf_static";
    case Topic::kSweep:
      return "sweep";
  }
  return "?";
}

std::unique_ptr<Publisher> Publisher::Create(const Participant& participant,
                                             const IpcConfig& config,
                                             const PublisherOptions& options,
                                             std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error != nullptr) *error = message;
    return std::unique_ptr<Publisher>();
  };
  const ConfigIssues issues = config.Validate();
  if (!issues.empty()) {
    return fail("invalid ipc configuration: " + issues.front().key + " " + issues.front().reason);
  }
  std::unique_ptr<Publisher> publisher(new Publisher());
  for (int i = 0; i < kTopicCount; ++i) {
    const auto topic_id = static_cast<Topic>(i);
    if (!options.topics[Index(topic_id)]) continue;
    const std::string name = wire::DdsTopicName(config, topic_id);
    if (name.empty()) continue;  // an optional topic switched off
    const dds_entity_t topic = dds_create_topic(participant.handle(), wire::Descriptor(topic_id),
                                                name.c_str(), nullptr, nullptr);
    if (topic < 0) {
      return fail("cannot create DDS topic '" + name + "': " + dds_strretcode(topic));
    }
    publisher->topics_[Index(topic_id)] = topic;
    dds_qos_t* qos = wire::MakeQos(topic_id, /*writer=*/true, 0);
    const dds_entity_t writer = dds_create_writer(participant.handle(), topic, qos, nullptr);
    dds_delete_qos(qos);
    if (writer < 0) {
      return fail("cannot create DDS writer for '" + name + "': " + dds_strretcode(writer));
    }
    publisher->writers_[Index(topic_id)] = writer;
    publisher->names_[Index(topic_id)] = name;
  }
  return publisher;
}

Publisher::~Publisher() {
  for (size_t i = 0; i < writers_.size(); ++i) {
    if (writers_[i] > 0) dds_delete(writers_[i]);
    if (topics_[i] > 0) dds_delete(topics_[i]);
  }
}

bool Publisher::Count(bool ok) {
  (ok ? published_ : failures_).fetch_add(1, std::memory_order_relaxed);
  return ok;
}

bool Publisher::PublishPose(const PoseWithCovarianceStamped& pose) {
  wire::PoseCovStampedMsg msg{};
  if (!wire::ToWire(pose, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(Topic::kPose)], &msg) == DDS_RETCODE_OK);
}

bool Publisher::PublishOdometry(const Odometry& odometry) {
  wire::OdometryMsg msg{};
  if (!wire::ToWire(odometry, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(Topic::kOdometry)], &msg) == DDS_RETCODE_OK);
}

bool Publisher::PublishOdomOdometry(const Odometry& odometry) {
  wire::OdometryMsg msg{};
  if (!wire::ToWire(odometry, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(Topic::kOdomOdometry)], &msg) == DDS_RETCODE_OK);
}

bool Publisher::WriteTf(Topic topic, const TFMessage& tf) {
  wire::TfStorage storage;
  wire::TFMessageMsg msg{};
  if (!wire::ToWire(tf, &storage, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(topic)], &msg) == DDS_RETCODE_OK);
}

bool Publisher::PublishTf(const TFMessage& tf) { return WriteTf(Topic::kTf, tf); }

bool Publisher::PublishTfStatic(const TFMessage& tf) { return WriteTf(Topic::kTfStatic, tf); }

bool Publisher::PublishHealth(const DiagnosticArray& health) {
  wire::DiagnosticStorage storage;
  wire::DiagnosticArrayMsg msg{};
  if (!wire::ToWire(health, &storage, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(Topic::kHealth)], &msg) == DDS_RETCODE_OK);
}

bool Publisher::PublishPath(const Path& path) {
  wire::PathStorage storage;
  wire::PathMsg msg{};
  if (!wire::ToWire(path, &storage, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(Topic::kPath)], &msg) == DDS_RETCODE_OK);
}

bool Publisher::PublishMap(const PointCloud2& map) {
  wire::PointCloudStorage storage;
  wire::PointCloud2Msg msg{};
  if (!wire::ToWire(map, &storage, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(Topic::kMap)], &msg) == DDS_RETCODE_OK);
}

bool Publisher::PublishSweep(const PointCloud2& sweep) {
  if (writers_[Index(Topic::kSweep)] <= 0) return Count(false);
  wire::PointCloudStorage storage;
  wire::PointCloud2Msg msg{};
  if (!wire::ToWire(sweep, &storage, &msg)) return Count(false);
  return Count(dds_write(writers_[Index(Topic::kSweep)], &msg) == DDS_RETCODE_OK);
}

int Publisher::MatchedSubscriptions(Topic topic) const {
  dds_publication_matched_status_t status{};
  if (dds_get_publication_matched_status(writers_[Index(topic)], &status) != DDS_RETCODE_OK) {
    return 0;
  }
  return static_cast<int>(status.current_count);
}

}  // namespace swlio::ipc

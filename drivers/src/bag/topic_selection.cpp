// Bag topics → swlio inputs, by message type (topic_selection.h).

#include "swlio/drivers/bag/topic_selection.h"

#include "swlio/drivers/bag/message_decoder.h"

namespace swlio::drivers::bag {
namespace {

constexpr std::string_view kDifopSuffix = "_difop";

bool IsDifopCompanion(const std::vector<BagTopic>& topics, const BagTopic& t) {
  const std::string& n = t.name;
  if (n.size() <= kDifopSuffix.size() || n.substr(n.size() - kDifopSuffix.size()) != kDifopSuffix) {
    return false;
  }
  const std::string base = n.substr(0, n.size() - kDifopSuffix.size());
  for (const BagTopic& other : topics) {
    if (other.name == base) return true;
  }
  return false;
}

bool Choose(const std::vector<BagTopic>& topics,
            TopicRole role,
            const std::string& named,
            const char* option,
            std::optional<uint32_t>* out,
            std::string* error) {
  std::vector<uint32_t> candidates;
  for (uint32_t i = 0; i < topics.size(); ++i) {
    const TopicRole r = RoleOf(ClassifyTopic(topics[i]));
    if (!named.empty() && topics[i].name == named) {
      if (r != role) {
        *error = "topic " + named + " (" + topics[i].type + ") is no " + RoleName(role) + " topic";
        return false;
      }
      *out = i;
      return true;
    }
    if (r == role && !(role == TopicRole::kLidar && IsDifopCompanion(topics, topics[i]))) {
      candidates.push_back(i);
    }
  }
  if (!named.empty()) {
    *error = "no topic " + named + " in the bag";
    return false;
  }
  if (candidates.size() > 1) {
    *error = std::string("several ") + RoleName(role) + " topics:";
    for (const uint32_t i : candidates) *error += " " + topics[i].name;
    *error += std::string("; choose one with ") + option;
    return false;
  }
  if (candidates.size() == 1) *out = candidates.front();
  return true;
}

}  // namespace

TopicRole RoleOf(RosMessageKind kind) {
  switch (kind) {
    case RosMessageKind::kRslidarScan:
    case RosMessageKind::kRslidarPacketLegacy:
    case RosMessageKind::kRslidarPacket:
    case RosMessageKind::kRslidarPacketEither:
    case RosMessageKind::kRobosenseScan:
    case RosMessageKind::kVelodyneScan:
    case RosMessageKind::kPointCloud2:
      return TopicRole::kLidar;
    case RosMessageKind::kImu:
      return TopicRole::kImu;
    case RosMessageKind::kNavSatFix:
      return TopicRole::kGnss;
    case RosMessageKind::kOdometry:
    case RosMessageKind::kTwistStamped:
      return TopicRole::kWheel;
    case RosMessageKind::kUnknown:
      break;
  }
  return TopicRole::kNone;
}

const char* RoleName(TopicRole role) {
  switch (role) {
    case TopicRole::kLidar:
      return "LiDAR";
    case TopicRole::kImu:
      return "IMU";
    case TopicRole::kGnss:
      return "GNSS";
    case TopicRole::kWheel:
      return "wheel odometry";
    case TopicRole::kNone:
      break;
  }
  return "unused";
}

bool SelectTopics(const std::vector<BagTopic>& topics,
                  const TopicChoice& choice,
                  SelectedTopics* out,
                  std::string* error) {
  *out = {};
  if (!Choose(topics, TopicRole::kLidar, choice.lidar, "--lidar-topic", &out->lidar, error) ||
      !Choose(topics, TopicRole::kImu, choice.imu, "--imu-topic", &out->imu, error) ||
      !Choose(topics, TopicRole::kGnss, choice.gnss, "--gnss-topic", &out->gnss, error) ||
      !Choose(topics, TopicRole::kWheel, choice.wheel, "--wheel-topic", &out->wheel, error)) {
    return false;
  }
  if (!out->lidar) return true;
  const std::string difop = topics[*out->lidar].name + std::string(kDifopSuffix);
  for (uint32_t i = 0; i < topics.size(); ++i) {
    if (topics[i].name == difop && RoleOf(ClassifyTopic(topics[i])) == TopicRole::kLidar) {
      out->lidar_info = i;
    }
  }
  return true;
}

}  // namespace swlio::drivers::bag

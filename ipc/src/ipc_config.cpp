#include "swlio/ipc/ipc_config.h"

#include <array>
#include <cctype>
#include <utility>

namespace swlio::ipc {
namespace {

/// ROS 2 topic names: [A-Za-z0-9_/], not starting with a digit or '/', no "//".
bool IsValidTopic(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.back() == '/') return false;
  if (std::isdigit(static_cast<unsigned char>(name.front())) != 0) return false;
  if (name.find("//") != std::string::npos) return false;
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '_' && c != '/') return false;
  }
  return true;
}

void CheckTopic(ConfigIssues& issues, const char* key, const std::string& name) {
  CheckThat(issues, IsValidTopic(name), key,
            "must be a ROS 2 topic name without leading '/' (letters, digits, '_', '/'), got '" +
                name + "'");
}

/// tf2 frame ids: not empty, no leading '/' (tf2 refuses them), no whitespace.
bool IsValidFrameId(const std::string& id) {
  if (id.empty() || id.front() == '/') return false;
  for (const char c : id) {
    if (std::isspace(static_cast<unsigned char>(c)) != 0) return false;
  }
  return true;
}

}  // namespace

ConfigIssues FrameNames::Validate() const {
  ConfigIssues issues;
  const std::array<std::pair<const char*, const std::string*>, 5> frames = {
      {{"map", &map},
       {"odom", &odom},
       {"base_link", &base_link},
       {"imu", &imu},
       {"lidar", &lidar}}};
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string& id = *frames[i].second;
    CheckThat(issues, IsValidFrameId(id), frames[i].first,
              "must be a tf2 frame id (not empty, no leading '/', no spaces), got '" + id + "'");
    for (size_t j = 0; j < i; ++j) {
      CheckThat(issues, id != *frames[j].second, frames[i].first,
                "must differ from " + std::string(frames[j].first) + " ('" + id +
                    "'): tf2 needs one frame per node of the tree");
    }
  }
  return issues;
}

ConfigIssues IpcConfig::Validate() const {
  ConfigIssues issues;
  // DDS domain ids map onto UDP ports; 232 is the largest that fits (DDSI-RTPS 2.2 §9.6.1.1).
  CheckInRange<int64_t>(issues, "domain_id", domain_id, 0, 232);
  CheckInRange<int64_t>(issues, "path_max_poses", path_max_poses, 1, 1'000'000);
  // 10 M points × 16 bytes still fits the uint32 row_step of sensor_msgs/PointCloud2.
  CheckInRange<int64_t>(issues, "map_max_points", map_max_points, 1'000, 10'000'000);
  CheckInRange(issues, "map_publish_period_s", map_publish_period_s, 0.0, 86'400.0);
  CheckThat(issues, stamp_clock == "realtime" || stamp_clock == "monotonic", "stamp_clock",
            "must be realtime or monotonic, got '" + stamp_clock + "'");
  CheckThat(issues, !dds_config_file.empty(), "dds_config_file", "must name a DDS XML file");
  CheckTopic(issues, "pose_topic", pose_topic);
  CheckTopic(issues, "odometry_topic", odometry_topic);
  CheckTopic(issues, "health_topic", health_topic);
  CheckTopic(issues, "path_topic", path_topic);
  CheckTopic(issues, "map_topic", map_topic);
  CheckTopic(issues, "odom_odometry_topic", odom_odometry_topic);
  CheckTopic(issues, "tf_topic", tf_topic);
  CheckTopic(issues, "tf_static_topic", tf_static_topic);
  if (!initialpose_topic.empty()) CheckTopic(issues, "initialpose_topic", initialpose_topic);
  if (!sweep_topic.empty()) CheckTopic(issues, "sweep_topic", sweep_topic);
  // At least 1 Hz (REP 105 consumers look map → odom up continuously).
  CheckInRange(issues, "map_odom_period_s", map_odom_period_s, 0.0, 1.0);
  AppendWithPrefix(issues, "frames", frames.Validate());
  return issues;
}

}  // namespace swlio::ipc

#include "swlio/daemon/config/daemon_config.h"

#include <algorithm>
#include <array>

namespace swlio::daemon {

namespace {

// The UDP ports of DDS domain d, from the default port mapping of OMG DDSI-RTPS (§9.6.1 in 2.3:
// PB 7400, DG 250, offsets 0, 10, 1, 11, PG 2), with the 50 participant indices that
// config/cyclonedds-loopback.xml allows: 7400 + 250·d + 0..111. With unicast discovery every
// participant of the domain sends its SPDP datagrams to each even port 7410..7510 of the band
// (measured: one swlio-echo, 3 in 3 s to each), so a LiDAR port there receives them.
constexpr int64_t kDdsPortBase = 7400;
constexpr int64_t kDdsDomainGain = 250;
constexpr int64_t kDdsBandPorts = 112;

void CheckOutsideDdsBand(ConfigIssues& issues,
                         const std::string& key,
                         uint16_t port,
                         int64_t domain_id) {
  const int64_t first = kDdsPortBase + kDdsDomainGain * domain_id;
  const int64_t last = first + kDdsBandPorts - 1;
  CheckThat(issues, port < first || port > last, key,
            "is one of DDS domain " + std::to_string(domain_id) + "'s ports (" +
                std::to_string(first) + "–" + std::to_string(last) +
                "): DDS discovery datagrams would arrive as bad LiDAR packets");
}

}  // namespace

bool IsLogLevelName(const std::string& level) {
  constexpr std::array<const char*, 7> kLevels = {"trace", "debug",    "info", "warn",
                                                  "error", "critical", "off"};
  for (const char* name : kLevels) {
    if (level == name) return true;
  }
  return false;
}

ConfigIssues LoggingConfig::Validate() const {
  ConfigIssues issues;
  const std::string levels = "must be trace, debug, info, warn, error, critical or off, got '";
  CheckThat(issues, IsLogLevelName(file_level), "file_level", levels + file_level + "'");
  CheckThat(
      issues, stderr_level == "auto" || IsLogLevelName(stderr_level), "stderr_level",
      "must be auto, trace, debug, info, warn, error, critical or off, got '" + stderr_level + "'");
  CheckThat(issues, journald == "auto" || journald == "true" || journald == "false", "journald",
            "must be auto, true or false, got '" + journald + "'");
  CheckThat(issues, !file_name.empty() && file_name.find('/') == std::string::npos, "file_name",
            "must be a plain file name");
  CheckInRange<int64_t>(issues, "max_file_size_mb", max_file_size_mb, 1, 1024);
  CheckInRange<int64_t>(issues, "max_files", max_files, 1, 1000);
  CheckInRange(issues, "status_period_s", status_period_s, 0.5, 3600.0);
  return issues;
}

ConfigIssues RecordConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues, !ring || !directory.empty(), "directory", "must be set when ring is on");
  CheckInRange(issues, "ring_minutes", ring_minutes, 0.5, 1440.0);
  CheckInRange(issues, "segment_s", segment_s, 1.0, 600.0);
  CheckThat(issues, segment_s <= ring_minutes * 60.0, "segment_s", "must not exceed ring_minutes");
  CheckInRange<int64_t>(issues, "max_disk_mb", max_disk_mb, 8, 1'000'000);
  CheckInRange(issues, "incident_before_s", incident_before_s, 0.0, 86400.0);
  CheckThat(issues, incident_before_s <= ring_minutes * 60.0, "incident_before_s",
            "must not exceed ring_minutes (the ring holds no more)");
  CheckInRange(issues, "incident_after_s", incident_after_s, 0.0, 3600.0);
  CheckInRange<int64_t>(issues, "incidents_max_count", incidents_max_count, 0, 10'000);
  CheckInRange<int64_t>(issues, "incidents_max_mb", incidents_max_mb, 0, 10'000'000);
  return issues;
}

std::vector<ThreadSchedConfig> DefaultThreadSchedule() {
  return {{"lidar_rx", 80, -1, -10},  {"imu_rx", 80, -1, -10}, {"propagator", 70, -1, -10},
          {"publisher", 60, -1, -10}, {"optimizer", 0, -1, 0}, {"loop_closure", 0, -1, 5}};
}

ConfigIssues RealtimeConfig::Validate() const {
  ConfigIssues issues;
  constexpr std::array<const char*, 10> kThreads = {
      "lidar_rx",  "imu_rx",   "can_rx",       "propagator",   "optimizer",
      "publisher", "recorder", "loop_closure", "localization", "control"};
  for (size_t i = 0; i < threads.size(); ++i) {
    const ThreadSchedConfig& t = threads[i];
    const std::string key = "threads[" + std::to_string(i) + "]";
    const bool known = std::find(kThreads.begin(), kThreads.end(), t.name) != kThreads.end();
    CheckThat(issues, known, key + ".name",
              "must be lidar_rx, imu_rx, can_rx, propagator, optimizer, publisher, recorder, "
              "loop_closure, localization or control, got '" +
                  t.name + "'");
    CheckInRange<int64_t>(issues, key + ".priority", t.priority, 0, 99);
    CheckInRange<int64_t>(issues, key + ".cpu", t.cpu, -1, 1023);
    CheckInRange<int64_t>(issues, key + ".nice", t.nice, -20, 19);
  }
  CheckInRange(issues, "max_sweep_lag_s", max_sweep_lag_s, 0.0, 60.0);
  return issues;
}

ConfigIssues MapFilesConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues, !localize || !load_path.empty(), "load_path",
            "localize needs a map to load (map.load_path or --map)");
  CheckThat(issues, !localize || save_path.empty(), "save_path",
            "a map is saved from loop closure, which is off while localizing");
  return issues;
}

ConfigIssues StateConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "save_period_s", save_period_s, 1.0, 86400.0);
  return issues;
}

ConfigIssues ControlConfig::Validate() const {
  ConfigIssues issues;
  // sockaddr_un::sun_path holds 108 bytes with the terminating NUL.
  CheckThat(
      issues, socket.size() < 108, "socket",
      "a UNIX socket path must be shorter than 108 bytes, got " + std::to_string(socket.size()));
  CheckThat(issues, group.find_first_of(" :/\n") == std::string::npos, "group",
            "must be a group name, got '" + group + "'");
  CheckInRange(issues, "request_timeout_s", request_timeout_s, 0.01, 60.0);
  CheckInRange(issues, "command_timeout_s", command_timeout_s, 0.1, 3600.0);
  CheckInRange<int64_t>(issues, "max_clients", max_clients, 1, 64);
  return issues;
}

ConfigIssues DaemonConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues, config_version == kConfigVersion, "config_version",
            "this build reads version " + std::to_string(kConfigVersion) + ", got " +
                std::to_string(config_version));
  AppendWithPrefix(issues, "lidar", lidar.Validate());
  CheckOutsideDdsBand(issues, "lidar.msop_port", lidar.msop_port, ipc.domain_id);
  CheckOutsideDdsBand(issues, "lidar.difop_port", lidar.difop_port, ipc.domain_id);
  AppendWithPrefix(issues, "imu", imu.Validate());
  AppendWithPrefix(issues, "can", can.Validate());
  AppendWithPrefix(issues, "estimator", estimator.Validate());
  ConfigIssues window_issues;
  for (ConfigIssue& issue : window.Validate()) {
    if (issue.key.rfind("odometry.", 0) != 0) window_issues.push_back(std::move(issue));
  }
  AppendWithPrefix(issues, "estimator.window", window_issues);
  AppendWithPrefix(issues, "estimator.loop_closure", loop_closure.Validate());
  CheckThat(issues, !window.wheel.enabled || can.enabled, "estimator.window.wheel.enabled",
            "needs the chassis odometry: can.enabled");
  AppendWithPrefix(issues, "estimator.localization", localization.Validate());
  AppendWithPrefix(issues, "map", map.Validate());
  AppendWithPrefix(issues, "state", state.Validate());
  AppendWithPrefix(issues, "ipc", ipc.Validate());
  AppendWithPrefix(issues, "logging", logging.Validate());
  AppendWithPrefix(issues, "record", record.Validate());
  AppendWithPrefix(issues, "realtime", realtime.Validate());
  AppendWithPrefix(issues, "control", control.Validate());
  return issues;
}

}  // namespace swlio::daemon

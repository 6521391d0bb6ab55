#pragma once
/// @file
/// The body of swlioctl's `status` reply: the estimator's state now, then the health message
/// the daemon published last (diagnostic_msgs/DiagnosticArray on ipc.health_topic, once a
/// second: rates over that second), every status with its level, message and values, so that
/// swlioctl says exactly what the health topic says. docs/control.md shows an example.

#include <cstdint>
#include <optional>
#include <string>

#include "swlio/daemon/runtime/health.h"
#include "swlio/ipc/messages.h"

namespace swlio::daemon {

struct StatusFacts {
  const char* mode = "";  ///< "mapping", "localizing", "odometry"
  bool ready = false;     ///< the READY=1 condition (sensors stream, the estimator has a state)
};

/// "ok", "warn", "error", "stale".
const char* LevelName(ipc::DiagnosticLevel level);

/// Lines "key: value", then per published status "<level> <name>: <message>" and its values
/// indented ("  key: value"). `published` empty: no health message yet (the first second).
std::string StatusReport(const HealthSnapshot& now,
                         const StatusFacts& facts,
                         const std::optional<ipc::DiagnosticArray>& published);

}  // namespace swlio::daemon

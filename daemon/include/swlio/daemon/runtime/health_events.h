#pragma once
/// @file
/// The periodic status report as structured events (event_log.h): the status line with its
/// counters as fields, and the warnings that go with it — queue drops, sensor clock jumps, the
/// estimator behind the LiDAR. systemd/README.md lists them and their fields.

#include <spdlog/common.h>

#include <string>
#include <vector>

#include "swlio/daemon/runtime/event_log.h"
#include "swlio/daemon/runtime/health.h"

namespace swlio::daemon {

/// One event to log with LogEvent.
struct HealthEvent {
  spdlog::level::level_enum level = spdlog::level::info;
  std::string event;
  std::string message;
  std::vector<EventField> fields;
};

/// The counters of the status line as fields: STATE (the estimator's tracking state), rates,
/// cumulative counters, and the loss/jump counts of the last interval (`rates`).
std::vector<EventField> StatusFields(const HealthSnapshot& now, const HealthRates& rates);

/// What a status report logs, in order: `status` (message `status_line`, StatusFields), then
/// `queue_drops` per queue that dropped, `clock_jump` per sensor whose clock jumped since the
/// previous report, and `estimator_behind` when sweeps were skipped since then.
std::vector<HealthEvent> StatusEvents(const HealthSnapshot& now,
                                      const HealthRates& rates,
                                      const std::string& status_line);

/// LogEvent for each.
void LogHealthEvents(const std::vector<HealthEvent>& events);

}  // namespace swlio::daemon

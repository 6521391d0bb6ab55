#pragma once
/// @file
/// health.csv, the black box's health history: one row per second with the daemon's counters
/// (cumulative: a reader differentiates them into rates) and gauges, so that an incident shows
/// how sensors, clocks, estimator, queues and CPU went before and after its event. Columns:
/// docs/blackbox.md.

#include <cstdint>
#include <string>

#include "swlio/daemon/runtime/health.h"

namespace swlio::daemon {

extern const char* const kHealthCsvHeader;

/// The process's own use of the computer.
struct ProcessUsage {
  double cpu_s = 0.0;   ///< user + system CPU time since the start
  double rss_mb = 0.0;  ///< resident set now
};
ProcessUsage ReadProcessUsage();

/// A CLOCK_REALTIME time in UTC through strftime's `format` (whole seconds).
std::string FormatUtc(int64_t realtime_ns, const char* format);

/// "2026-12-04T14:32:07.120Z" for a CLOCK_REALTIME time.
std::string UtcIso(int64_t realtime_ns);

/// One row (no newline) for the snapshot `s` taken at daemon time `t_ns`.
std::string HealthCsvRow(const HealthSnapshot& s,
                         int64_t t_ns,
                         int64_t realtime_ns,
                         const ProcessUsage& usage);

}  // namespace swlio::daemon

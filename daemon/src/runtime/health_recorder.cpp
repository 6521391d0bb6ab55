#include <cstdio>

#include "swlio/daemon/runtime/health.h"

namespace swlio::daemon {
namespace {

std::string Mb(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", static_cast<double>(bytes) / 1e6);
  return text;
}

}  // namespace

ipc::DiagnosticStatus RecorderStatus(const HealthSnapshot& s) {
  const RecorderCounters& c = s.recorder;
  ipc::DiagnosticStatus d;
  d.name = c.ring ? "swlio: black box" : "swlio: recording";
  d.hardware_id = "swlio";
  d.level = ipc::DiagnosticLevel::kOk;
  d.message =
      c.ring ? "recording the last minutes; " + std::to_string(c.incidents.kept) + " incidents kept"
             : "recording";
  if (c.stopped) {
    d.level = ipc::DiagnosticLevel::kError;
    d.message = "stopped, nothing is recorded: " + c.error;
  } else if (c.incidents.failed > 0) {
    d.level = ipc::DiagnosticLevel::kWarn;
    d.message += "; " + c.incidents.last_error;
  }
  d.values = {{"lidar_packets", std::to_string(c.lidar_packets)},
              {"serial_bytes", std::to_string(c.serial_bytes)},
              {"discarded", std::to_string(c.discarded)}};
  if (!c.ring) return d;
  char span[32];
  std::snprintf(span, sizeof span, "%.1f", c.ring_span_s);
  d.values.insert(d.values.end(), {{"segments", std::to_string(c.segments)},
                                   {"ring_mb", Mb(c.ring_bytes)},
                                   {"ring_span_s", span},
                                   {"segments_deleted", std::to_string(c.segments_deleted)},
                                   {"incident_events", std::to_string(c.incidents.events)},
                                   {"incidents_kept", std::to_string(c.incidents.kept)},
                                   {"incidents_pending", std::to_string(c.incidents.pending)},
                                   {"incidents_failed", std::to_string(c.incidents.failed)},
                                   {"incidents_removed", std::to_string(c.incidents.removed)},
                                   {"last_incident", c.incidents.last_incident}});
  return d;
}

}  // namespace swlio::daemon

#include "swlio/daemon/control/status_report.h"

#include <cstdio>

namespace swlio::daemon {

const char* LevelName(ipc::DiagnosticLevel level) {
  switch (level) {
    case ipc::DiagnosticLevel::kOk:
      return "ok";
    case ipc::DiagnosticLevel::kWarn:
      return "warn";
    case ipc::DiagnosticLevel::kError:
      return "error";
    case ipc::DiagnosticLevel::kStale:
      return "stale";
  }
  return "unknown";
}

std::string StatusReport(const HealthSnapshot& now,
                         const StatusFacts& facts,
                         const std::optional<ipc::DiagnosticArray>& published) {
  std::string out;
  auto line = [&out](const std::string& key, const std::string& value) {
    out += key + ": " + value + "\n";
  };
  line("state", ToString(now.optimizer.tracking));
  line("mode", facts.mode);
  line("ready", facts.ready ? "true" : "false");
  line("sweeps", std::to_string(now.optimizer.processed));
  line("drops", std::to_string(TotalDrops(now)));
  line("reinitializations", std::to_string(now.optimizer.reinitializations));
  line("operator_resets", std::to_string(now.optimizer.operator_resets));
  if (!published) {
    line("health", "none published yet (once a second)");
    return out;
  }
  char age[32];
  std::snprintf(age, sizeof age, "%.2f", static_cast<double>(now.t_ns - published->t_ns) * 1e-9);
  line("health_age_s", age);
  for (const ipc::DiagnosticStatus& s : published->status) {
    out += std::string(LevelName(s.level)) + " " + s.name + ": " + s.message + "\n";
    for (const ipc::KeyValue& kv : s.values) out += "  " + kv.key + ": " + kv.value + "\n";
  }
  return out;
}

}  // namespace swlio::daemon

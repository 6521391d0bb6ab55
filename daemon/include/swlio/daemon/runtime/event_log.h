#pragma once
/// @file
/// Structured events: a log line (file, stderr) that, in the journal, also carries
/// SWLIO_EVENT=<event> and one SWLIO_<NAME>=value field per EventField, so that
/// `journalctl -u swliod SWLIO_EVENT=divergence` finds it (journal_sink.h). The events and their
/// fields are listed in systemd/README.md.

#include <spdlog/common.h>

#include <string>
#include <string_view>
#include <vector>

namespace swlio::daemon {

/// One field of an event. `name` is UPPER_SNAKE ([A-Z0-9_]); other characters are replaced by
/// '_' in the journal (JournalFieldName), where it becomes SWLIO_<name>.
struct EventField {
  std::string name;
  std::string value;
};

/// Logs `message` at `level` through spdlog (file, stderr) and, when the journal sink is on,
/// with SWLIO_EVENT=<event> and the fields (SWLIO_<NAME>=value) in the journal entry.
/// `event` is lower_snake_case (other characters become '_'). Logs through spdlog's default
/// logger (SetupLogging makes it), on the calling thread.
void LogEvent(spdlog::level::level_enum level,
              std::string_view event,
              const std::string& message,
              const std::vector<EventField>& fields = {});

}  // namespace swlio::daemon

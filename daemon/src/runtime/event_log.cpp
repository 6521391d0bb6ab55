#include "swlio/daemon/runtime/event_log.h"

#include <spdlog/spdlog.h>

#include "swlio/daemon/runtime/journal_sink.h"

namespace swlio::daemon {

void LogEvent(spdlog::level::level_enum level,
              std::string_view event,
              const std::string& message,
              const std::vector<EventField>& fields) {
  spdlog::logger* logger = spdlog::default_logger_raw();
  if (logger == nullptr || !logger->should_log(level)) return;
  const PendingEvent pending{event, &fields};
  const ScopedPendingEvent scope(pending);  // the journal sink runs on this thread
  logger->log(spdlog::source_loc{}, level, spdlog::string_view_t(message));  // not a format
}

}  // namespace swlio::daemon

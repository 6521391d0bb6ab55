#pragma once
/// @file
/// A spdlog sink that writes every record to the systemd journal through its native protocol
/// (sd_journal_sendv(3)): MESSAGE, PRIORITY, SYSLOG_IDENTIFIER, TID, CODE_FILE/CODE_LINE/
/// CODE_FUNC when the record has its source, and for records made by LogEvent (event_log.h)
/// SWLIO_EVENT and SWLIO_<NAME> per field. Field name rules: systemd.journal-fields(7) and
/// sd_journal_print(3) — uppercase letters, digits and '_', not starting with '_' (those are
/// the trusted fields journald adds itself).

#include <spdlog/sinks/base_sink.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "swlio/daemon/runtime/event_log.h"

namespace swlio::daemon {

/// The syslog priority (journal field PRIORITY, 0 emerg … 7 debug, syslog(3)) of a spdlog
/// level: trace and debug → 7, info → 6, warn → 4, err → 3, critical → 2.
int SyslogPriority(spdlog::level::level_enum level);

/// The journal field of an event field: "SWLIO_" + `name` upper-cased, every character outside
/// [A-Z0-9_] replaced by '_', cut to the journal's 64 characters. "EVENT" becomes "EVENT_" (the
/// event's own name is SWLIO_EVENT); an empty name becomes "SWLIO_FIELD".
std::string JournalFieldName(std::string_view name);

/// An event name as lower_snake_case: lower-cased, every character outside [a-z0-9_] → '_'.
std::string SanitizeEventName(std::string_view event);

/// The event that LogEvent is logging on this thread, for the journal sink (which runs on the
/// logging thread: the logger is synchronous).
struct PendingEvent {
  std::string_view event;
  const std::vector<EventField>* fields = nullptr;
};

/// Sets the calling thread's pending event for its lifetime.
class ScopedPendingEvent {
 public:
  explicit ScopedPendingEvent(const PendingEvent& event);
  ~ScopedPendingEvent();
  ScopedPendingEvent(const ScopedPendingEvent&) = delete;
  ScopedPendingEvent& operator=(const ScopedPendingEvent&) = delete;

 private:
  const PendingEvent* previous_;
};

/// The calling thread's pending event; nullptr outside LogEvent.
const PendingEvent* CurrentPendingEvent();

/// The fields of the journal entry for `msg` ("KEY=value" each), `event` may be nullptr.
std::vector<std::string> JournalEntryFields(const spdlog::details::log_msg& msg,
                                            const PendingEvent* event,
                                            std::string_view identifier);

/// Sends each record with sd_journal_sendv(); errors (no journald: the socket is missing) are
/// counted, never thrown: logging must not stop the daemon.
class JournalSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit JournalSink(std::string identifier = "swliod") : identifier_(std::move(identifier)) {}
  /// Records sd_journal_sendv() refused.
  uint64_t send_errors() const { return send_errors_.load(std::memory_order_relaxed); }

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override;
  void flush_() override {}

 private:
  std::string identifier_;
  std::atomic<uint64_t> send_errors_{0};
};

}  // namespace swlio::daemon

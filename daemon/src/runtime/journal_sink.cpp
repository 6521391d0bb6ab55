// The journal sink. sd_journal_sendv(3) takes one iovec per field, "FIELD=value"; values may hold
// any bytes, newlines included (the library then sends the field in the binary form of the
// native protocol, https://systemd.io/JOURNAL_NATIVE_PROTOCOL/). journald adds the trusted fields
// (_PID, _SYSTEMD_UNIT, …) itself, which is what `journalctl -u swliod` matches.

#include "swlio/daemon/runtime/journal_sink.h"

#include <sys/uio.h>
// Without it sd-journal.h turns sd_journal_sendv into a macro adding CODE_FILE/CODE_LINE/
// CODE_FUNC of this file (sd_journal_print(3)); the record's own source is sent instead.
#define SD_JOURNAL_SUPPRESS_LOCATION
#include <systemd/sd-journal.h>

#include <cctype>
#include <string>
#include <utility>

namespace swlio::daemon {
namespace {

// journald drops a field whose name is longer, starts with a digit or '_', or holds anything but
// [A-Z0-9_] (journal_field_valid() in systemd's journal code; systemd.journal-fields(7)).
constexpr size_t kJournalFieldNameMax = 64;
constexpr std::string_view kJournalFieldPrefix = "SWLIO_";

thread_local const PendingEvent* tls_pending_event = nullptr;

std::string JournalField(std::string_view name, std::string_view value) {
  std::string f;
  f.reserve(name.size() + 1 + value.size());
  f.append(name).append("=").append(value);
  return f;
}

}  // namespace

int SyslogPriority(spdlog::level::level_enum level) {
  switch (level) {
    case spdlog::level::critical:
      return 2;  // LOG_CRIT
    case spdlog::level::err:
      return 3;  // LOG_ERR
    case spdlog::level::warn:
      return 4;  // LOG_WARNING
    case spdlog::level::info:
      return 6;  // LOG_INFO
    default:
      return 7;  // LOG_DEBUG: debug and trace
  }
}

std::string JournalFieldName(std::string_view name) {
  std::string out(kJournalFieldPrefix);
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    out += std::isalnum(u) != 0 && u < 0x80 ? static_cast<char>(std::toupper(u)) : '_';
  }
  if (name.empty()) out += "FIELD";
  if (out == "SWLIO_EVENT") out += '_';
  if (out.size() > kJournalFieldNameMax) out.resize(kJournalFieldNameMax);
  return out;
}

std::string SanitizeEventName(std::string_view event) {
  std::string out;
  out.reserve(event.size());
  for (const char c : event) {
    const auto u = static_cast<unsigned char>(c);
    out += std::isalnum(u) != 0 && u < 0x80 ? static_cast<char>(std::tolower(u)) : '_';
  }
  return out;
}

ScopedPendingEvent::ScopedPendingEvent(const PendingEvent& event) : previous_(tls_pending_event) {
  tls_pending_event = &event;
}

ScopedPendingEvent::~ScopedPendingEvent() { tls_pending_event = previous_; }

const PendingEvent* CurrentPendingEvent() { return tls_pending_event; }

std::vector<std::string> JournalEntryFields(const spdlog::details::log_msg& msg,
                                            const PendingEvent* event,
                                            std::string_view identifier) {
  std::vector<std::string> fields;
  fields.reserve(8 + (event != nullptr && event->fields != nullptr ? event->fields->size() : 0));
  fields.push_back(
      JournalField("MESSAGE", std::string_view(msg.payload.data(), msg.payload.size())));
  fields.push_back(JournalField("PRIORITY", std::to_string(SyslogPriority(msg.level))));
  fields.push_back(JournalField("SYSLOG_IDENTIFIER", identifier));
  fields.push_back(JournalField("TID", std::to_string(msg.thread_id)));
  if (!msg.source.empty()) {
    fields.push_back(JournalField("CODE_FILE", msg.source.filename));
    fields.push_back(JournalField("CODE_LINE", std::to_string(msg.source.line)));
    if (msg.source.funcname != nullptr)
      fields.push_back(JournalField("CODE_FUNC", msg.source.funcname));
  }
  if (event != nullptr) {
    fields.push_back(JournalField("SWLIO_EVENT", SanitizeEventName(event->event)));
    if (event->fields != nullptr) {
      for (const EventField& f : *event->fields) {
        fields.push_back(JournalField(JournalFieldName(f.name), f.value));
      }
    }
  }
  return fields;
}

void JournalSink::sink_it_(const spdlog::details::log_msg& msg) {
  const std::vector<std::string> fields = JournalEntryFields(msg, tls_pending_event, identifier_);
  std::vector<iovec> iov(fields.size());
  for (size_t i = 0; i < fields.size(); ++i) {
    iov[i].iov_base = const_cast<char*>(fields[i].data());  // sendv only reads
    iov[i].iov_len = fields[i].size();
  }
  if (sd_journal_sendv(iov.data(), static_cast<int>(iov.size())) < 0) {
    send_errors_.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace swlio::daemon

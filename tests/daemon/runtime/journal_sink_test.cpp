#include "swlio/daemon/runtime/journal_sink.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace swlio::daemon {
namespace {

TEST(JournalSink, LevelsMapToSyslogPriorities) {
  EXPECT_EQ(SyslogPriority(spdlog::level::trace), 7);  // LOG_DEBUG
  EXPECT_EQ(SyslogPriority(spdlog::level::debug), 7);
  EXPECT_EQ(SyslogPriority(spdlog::level::info), 6);      // LOG_INFO
  EXPECT_EQ(SyslogPriority(spdlog::level::warn), 4);      // LOG_WARNING
  EXPECT_EQ(SyslogPriority(spdlog::level::err), 3);       // LOG_ERR
  EXPECT_EQ(SyslogPriority(spdlog::level::critical), 2);  // LOG_CRIT
}

TEST(JournalSink, FieldNamesFollowTheJournalRules) {
  EXPECT_EQ(JournalFieldName("STATE"), "SWLIO_STATE");
  EXPECT_EQ(JournalFieldName("lidar rate-hz"), "SWLIO_LIDAR_RATE_HZ");
  EXPECT_EQ(JournalFieldName("p99.ms/é"), "SWLIO_P99_MS___");  // é is two bytes
  EXPECT_EQ(JournalFieldName("_X"), "SWLIO__X");               // never starts with '_': the prefix
  EXPECT_EQ(JournalFieldName(""), "SWLIO_FIELD");
  EXPECT_EQ(JournalFieldName("event"), "SWLIO_EVENT_");  // not the event's own field
  const std::string long_name = JournalFieldName(std::string(100, 'a'));
  EXPECT_EQ(long_name.size(), 64u);
  EXPECT_EQ(long_name, "SWLIO_" + std::string(58, 'A'));
}

TEST(JournalSink, EventNamesAreLowerSnakeCase) {
  EXPECT_EQ(SanitizeEventName("clock_jump"), "clock_jump");
  EXPECT_EQ(SanitizeEventName("Clock-Jump 2"), "clock_jump_2");
}

std::map<std::string, std::string> AsMap(const std::vector<std::string>& fields) {
  std::map<std::string, std::string> m;
  for (const std::string& f : fields) {
    const size_t eq = f.find('=');
    EXPECT_NE(eq, std::string::npos) << f;
    EXPECT_TRUE(m.emplace(f.substr(0, eq), f.substr(eq + 1)).second) << "repeated: " << f;
  }
  return m;
}

TEST(JournalSink, EntryCarriesTheRecordAndTheEvent) {
  const spdlog::source_loc where{"daemon/src/x.cpp", 42, "Run"};
  spdlog::details::log_msg msg(where, "swlio", spdlog::level::warn, "queue full");
  const std::vector<EventField> fields = {{"QUEUE", "lidar"}, {"dropped", "3"}};
  const PendingEvent event{"queue_drops", &fields};
  auto m = AsMap(JournalEntryFields(msg, &event, "swliod"));
  EXPECT_EQ(m["MESSAGE"], "queue full");
  EXPECT_EQ(m["PRIORITY"], "4");
  EXPECT_EQ(m["SYSLOG_IDENTIFIER"], "swliod");
  EXPECT_EQ(m["TID"], std::to_string(msg.thread_id));
  EXPECT_EQ(m["CODE_FILE"], "daemon/src/x.cpp");
  EXPECT_EQ(m["CODE_LINE"], "42");
  EXPECT_EQ(m["CODE_FUNC"], "Run");
  EXPECT_EQ(m["SWLIO_EVENT"], "queue_drops");
  EXPECT_EQ(m["SWLIO_QUEUE"], "lidar");
  EXPECT_EQ(m["SWLIO_DROPPED"], "3");
  EXPECT_EQ(m.size(), 10u);

  spdlog::details::log_msg plain("swlio", spdlog::level::info, "no source");
  m = AsMap(JournalEntryFields(plain, nullptr, "swliod"));
  EXPECT_EQ(m.count("CODE_FILE"), 0u);
  EXPECT_EQ(m.count("SWLIO_EVENT"), 0u);
  EXPECT_EQ(m["PRIORITY"], "6");
}

TEST(JournalSink, PendingEventIsScopedToTheThread) {
  EXPECT_EQ(CurrentPendingEvent(), nullptr);
  const PendingEvent outer{"outer", nullptr};
  {
    const ScopedPendingEvent a(outer);
    EXPECT_EQ(CurrentPendingEvent(), &outer);
    const PendingEvent inner{"inner", nullptr};
    {
      const ScopedPendingEvent b(inner);
      EXPECT_EQ(CurrentPendingEvent(), &inner);
    }
    EXPECT_EQ(CurrentPendingEvent(), &outer);
  }
  EXPECT_EQ(CurrentPendingEvent(), nullptr);
}

}  // namespace
}  // namespace swlio::daemon

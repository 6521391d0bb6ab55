// LogEvent and the journal sink end to end: what reaches a journal socket (fake_journal.h).

#include "swlio/daemon/runtime/event_log.h"

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <string>
#include <vector>

#include "fake_journal.h"
#include "swlio/daemon/runtime/logging.h"

namespace swlio::daemon {
namespace {

using test::JournalEntry;
using test::ParseJournalDatagram;
using test::RunWithFakeJournal;

/// A logger with only the journal sink (or none, `journald` "false"), in the forked child.
void SetupJournalOnly(const char* journald) {
  LoggingConfig config;
  config.directory.clear();  // no files
  config.stderr_level = "off";
  config.journald = journald;
  std::string error;
  if (SetupLogging(config, &error) == nullptr) _exit(3);
}

std::string FieldValue(const JournalEntry& e, const std::string& key) {
  const auto it = e.find(key);
  return it == e.end() ? "<absent>" : it->second;
}

std::vector<JournalEntry> ParseEntries(const test::FakeJournalRun& run) {
  std::vector<JournalEntry> entries;
  for (const std::string& d : run.datagrams) {
    const auto e = ParseJournalDatagram(d);
    EXPECT_TRUE(e.has_value()) << "malformed datagram: " << d;
    if (e) entries.push_back(*e);
  }
  return entries;
}

#define SKIP_WITHOUT_NAMESPACES(run)                                                          \
  if (!(run).skipped.empty())                                                                 \
  GTEST_SKIP() << "no private mount namespace for a fake /run/systemd/journal/socket (needs " \
                  "root or user namespaces): "                                                \
               << (run).skipped

TEST(EventLog, EventsReachTheJournalWithTheirFields) {
  const test::FakeJournalRun run = RunWithFakeJournal([] {
    SetupJournalOnly("true");
    LogEvent(spdlog::level::warn, "divergence", "estimator: state diverged {not a format}",
             {{"REASON", "imu_bias"}, {"sweep end.s", "12.500"}});
    spdlog::info("plain line {}", 7);
    LogEvent(spdlog::level::err, "Clock-Jump", "two\nlines", {});
    SPDLOG_LOGGER_CRITICAL(spdlog::default_logger_raw(), "with its source");
    spdlog::debug("debug line");
  });
  SKIP_WITHOUT_NAMESPACES(run);
  ASSERT_TRUE(run.error.empty()) << run.error;
  const std::vector<JournalEntry> e = ParseEntries(run);
  ASSERT_EQ(e.size(), 5u);

  EXPECT_EQ(FieldValue(e[0], "MESSAGE"), "estimator: state diverged {not a format}");
  EXPECT_EQ(FieldValue(e[0], "PRIORITY"), "4");
  EXPECT_EQ(FieldValue(e[0], "SYSLOG_IDENTIFIER"), "swliod");
  EXPECT_EQ(FieldValue(e[0], "SWLIO_EVENT"), "divergence");
  EXPECT_EQ(FieldValue(e[0], "SWLIO_REASON"), "imu_bias");
  EXPECT_EQ(FieldValue(e[0], "SWLIO_SWEEP_END_S"), "12.500");
  EXPECT_NE(FieldValue(e[0], "TID"), "<absent>");
  EXPECT_GT(std::stol(FieldValue(e[0], "TID")), 0);
  EXPECT_EQ(e[0].count("CODE_FILE"), 0u);  // LogEvent has no source location

  EXPECT_EQ(FieldValue(e[1], "MESSAGE"), "plain line 7");
  EXPECT_EQ(FieldValue(e[1], "PRIORITY"), "6");
  EXPECT_EQ(e[1].count("SWLIO_EVENT"), 0u);  // not an event: no event fields leak over

  EXPECT_EQ(FieldValue(e[2], "MESSAGE"), "two\nlines");  // the binary field form
  EXPECT_EQ(FieldValue(e[2], "PRIORITY"), "3");
  EXPECT_EQ(FieldValue(e[2], "SWLIO_EVENT"), "clock_jump");

  EXPECT_EQ(FieldValue(e[3], "MESSAGE"), "with its source");
  EXPECT_EQ(FieldValue(e[3], "PRIORITY"), "2");
  EXPECT_NE(FieldValue(e[3], "CODE_FILE").find("event_log_test.cpp"), std::string::npos);
  EXPECT_GT(std::stoi(FieldValue(e[3], "CODE_LINE")), 0);
  EXPECT_NE(FieldValue(e[3], "CODE_FUNC"), "<absent>");

  EXPECT_EQ(FieldValue(e[4], "MESSAGE"), "debug line");
  EXPECT_EQ(FieldValue(e[4], "PRIORITY"), "7");
}

TEST(EventLog, NothingReachesTheJournalWhenItIsOff) {
  const test::FakeJournalRun run = RunWithFakeJournal([] {
    SetupJournalOnly("false");
    LogEvent(spdlog::level::warn, "divergence", "estimator: state diverged");
    spdlog::warn("plain warning");
  });
  SKIP_WITHOUT_NAMESPACES(run);
  ASSERT_TRUE(run.error.empty()) << run.error;
  EXPECT_TRUE(run.datagrams.empty());
}

TEST(EventLog, ParserReadsBothFieldForms) {
  // The parser the tests above rely on, against bytes written by hand from the protocol text.
  std::string d = "MESSAGE=hi\nBIN\n";
  const char size[8] = {3, 0, 0, 0, 0, 0, 0, 0};
  d.append(size, 8).append("a\nb\n").append("PRIORITY=6\n");
  const auto e = ParseJournalDatagram(d);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(FieldValue(*e, "MESSAGE"), "hi");
  EXPECT_EQ(FieldValue(*e, "BIN"), "a\nb");
  EXPECT_EQ(FieldValue(*e, "PRIORITY"), "6");
  EXPECT_FALSE(ParseJournalDatagram("MESSAGE=no newline").has_value());
  EXPECT_FALSE(ParseJournalDatagram(std::string("BIN\n\x09\0\0\0\0\0\0\0ab\n", 15)).has_value());
}

}  // namespace
}  // namespace swlio::daemon

#include "swlio/daemon/runtime/logging.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "swlio/daemon/runtime/journal_sink.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Logging, WritesFileWithLevelFilter) {
  LoggingConfig config;
  config.directory = (test::MakeTempDir("log") / "nested").string();  // created on demand
  config.file_level = "info";
  config.stderr_level = "off";
  std::string error;
  auto logger = SetupLogging(config, &error);
  ASSERT_NE(logger, nullptr) << error;
  logger->info("lidar packets={} drops={}", 7500, 0);
  logger->debug("this is below the file level");
  logger->flush();
  const std::string text = ReadFile(std::filesystem::path(config.directory) / "swliod.log");
  EXPECT_NE(text.find("info  ["), std::string::npos) << text;
  EXPECT_NE(text.find("lidar packets=7500 drops=0"), std::string::npos);
  EXPECT_EQ(text.find("below the file level"), std::string::npos);
}

TEST(Logging, RotatesAtTheConfiguredSize) {
  LoggingConfig config;
  const auto dir = test::MakeTempDir("logrot");
  config.directory = dir.string();
  config.stderr_level = "off";
  config.max_file_size_mb = 1;
  config.max_files = 2;
  std::string error;
  auto logger = SetupLogging(config, &error);
  ASSERT_NE(logger, nullptr) << error;
  const std::string line(200, 'x');
  for (int i = 0; i < 15000; ++i) logger->info("{} {}", i, line);  // ≈ 3.3 MB
  logger->flush();
  EXPECT_TRUE(std::filesystem::exists(dir / "swliod.log"));
  EXPECT_TRUE(std::filesystem::exists(dir / "swliod.1.log"));
  EXPECT_TRUE(std::filesystem::exists(dir / "swliod.2.log"));
  EXPECT_FALSE(std::filesystem::exists(dir / "swliod.3.log"));  // max_files bounds disk use
  EXPECT_LE(std::filesystem::file_size(dir / "swliod.1.log"), 1024u * 1024u);
}

TEST(Logging, UnwritableDirectoryIsAnError) {
  const auto dir = test::MakeTempDir("logbad");
  std::ofstream(dir / "file") << "x";
  LoggingConfig config;
  config.directory = (dir / "file").string();  // a file, not a directory
  std::string error;
  EXPECT_EQ(SetupLogging(config, &error), nullptr);
  EXPECT_NE(error.find("cannot open log file"), std::string::npos) << error;
}

/// Sets or clears an environment variable for one test, restoring it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    const char* old = std::getenv(name);
    if (old != nullptr) old_ = old;
    had_ = old != nullptr;
    if (value != nullptr) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (had_) {
      setenv(name_, old_.c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

/// JOURNAL_STREAM's text for an open file: "<device>:<inode>".
std::string StreamOf(int fd) {
  struct stat st {};
  EXPECT_EQ(fstat(fd, &st), 0);
  return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
}

TEST(Logging, SystemdIsSeenInTheEnvironmentAndStderr) {
  const auto dir = test::MakeTempDir("journalstream");
  const int stderr_like = open((dir / "a").c_str(), O_CREAT | O_WRONLY, 0644);
  const int other = open((dir / "b").c_str(), O_CREAT | O_WRONLY, 0644);
  ASSERT_GE(stderr_like, 0);
  ASSERT_GE(other, 0);
  const std::string ours = StreamOf(stderr_like);
  const std::string theirs = StreamOf(other);
  const char* id = "0123456789abcdef0123456789abcdef";
  EXPECT_FALSE(StartedBySystemd(nullptr, nullptr, stderr_like));
  EXPECT_TRUE(StartedBySystemd(ours.c_str(), nullptr, stderr_like));  // stderr is the journal
  EXPECT_TRUE(StartedBySystemd(ours.c_str(), id, stderr_like));
  EXPECT_TRUE(StartedBySystemd(nullptr, id, stderr_like));  // a service logging elsewhere
  // Inherited from a service higher up (a desktop session, a CI runner): not our stderr.
  EXPECT_FALSE(StartedBySystemd(theirs.c_str(), nullptr, stderr_like));
  EXPECT_FALSE(StartedBySystemd(theirs.c_str(), id, stderr_like));
  EXPECT_FALSE(StartedBySystemd("garbage", nullptr, stderr_like));
  EXPECT_FALSE(StartedBySystemd((ours + "x").c_str(), nullptr, stderr_like));
  close(stderr_like);
  close(other);
}

TEST(Logging, JournaldAutoFollowsSystemdsEnvironment) {
  LoggingConfig config;
  ASSERT_EQ(config.journald, "auto");
  {
    const ScopedEnv stream("JOURNAL_STREAM", nullptr);
    const ScopedEnv invocation("INVOCATION_ID", nullptr);
    EXPECT_FALSE(StartedBySystemd());
    EXPECT_FALSE(JournaldOn(config));
    config.journald = "true";
    EXPECT_TRUE(JournaldOn(config));
    config.journald = "auto";
  }
  {
    const ScopedEnv stream("JOURNAL_STREAM", StreamOf(STDERR_FILENO).c_str());
    const ScopedEnv invocation("INVOCATION_ID", nullptr);
    EXPECT_TRUE(JournaldOn(config));
  }
  {
    const ScopedEnv stream("JOURNAL_STREAM", nullptr);
    const ScopedEnv invocation("INVOCATION_ID", "0123456789abcdef0123456789abcdef");
    EXPECT_TRUE(JournaldOn(config));
    config.journald = "false";
    EXPECT_FALSE(JournaldOn(config));
  }
}

TEST(Logging, StderrIsOffWhileTheJournalSinkIsOnUnlessSetExplicitly) {
  LoggingConfig config;
  ASSERT_EQ(config.stderr_level, "auto");
  EXPECT_EQ(EffectiveStderrLevel(config, false), "info");
  EXPECT_EQ(EffectiveStderrLevel(config, true), "off");
  config.stderr_level = "warn";
  EXPECT_EQ(EffectiveStderrLevel(config, true), "warn");
  EXPECT_EQ(EffectiveStderrLevel(config, false), "warn");

  // The sinks SetupLogging makes: stderr first, then the journal sink when on.
  config.directory.clear();
  config.stderr_level = "auto";
  config.journald = "true";
  std::string error;
  auto logger = SetupLogging(config, &error);
  ASSERT_NE(logger, nullptr) << error;
  ASSERT_EQ(logger->sinks().size(), 2u);
  EXPECT_EQ(logger->sinks()[0]->level(), spdlog::level::off);
  EXPECT_NE(dynamic_cast<JournalSink*>(logger->sinks()[1].get()), nullptr);
  EXPECT_EQ(logger->sinks()[1]->level(), spdlog::level::trace);
  config.journald = "false";
  logger = SetupLogging(config, &error);
  ASSERT_NE(logger, nullptr) << error;
  ASSERT_EQ(logger->sinks().size(), 1u);
  EXPECT_EQ(logger->sinks()[0]->level(), spdlog::level::info);
}

}  // namespace
}  // namespace swlio::daemon

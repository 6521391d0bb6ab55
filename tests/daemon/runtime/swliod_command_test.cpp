// swliod as systemd runs it: a bad configuration exits with EX_CONFIG (not restarted), a good
// one runs until SIGTERM and stops cleanly with its status in the log. And its configuration
// commands: --print-config FILE | --check-config -. And the time offset it keeps across restarts.

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "swlio/daemon/config/config_loader.h"
#include "swlio/daemon/config/config_printer.h"
#include "test_data.h"
#include "udp_port.h"

extern char** environ;

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;

pid_t Spawn(const std::vector<std::string>& args, const std::filesystem::path& out) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

int WaitExit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Swliod() { return ::swlio::test::ToolPath("swliod").string(); }

/// A configuration with no sensor behind it (quiet ports, an absent tty), logging into DIR/log.
std::string QuietConfig(const std::filesystem::path& dir, int domain) {
  std::ostringstream c;
  c << "config_version: 1\nlidar:\n  bind_address: 127.0.0.1\n  msop_port: " << test::QuietUdpPort()
    << "\n  difop_port: " << test::QuietUdpPort()
    << "\nimu:\n  device: " << (dir / "absent-tty").string()
    << "\n  configure_on_start: false\nipc:\n  dds_config_file: "
    << (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string()
    << "\n  domain_id: " << domain << "\nlogging:\n  directory: " << (dir / "log").string()
    << "\n  status_period_s: 0.5\n";
  return c.str();
}

/// Runs swliod on DIR/swlio.yaml for `run_ms`, then SIGTERM; its exit code.
int RunFor(const std::filesystem::path& dir, int run_ms) {
  const pid_t pid = Spawn({Swliod(), "--config", (dir / "swlio.yaml").string()}, dir / "out");
  std::this_thread::sleep_for(std::chrono::milliseconds(run_ms));
  kill(pid, SIGTERM);
  return WaitExit(pid);
}

TEST(SwliodCommand, ABadConfigurationExitsWithExConfig) {
  const auto dir = test::MakeTempDir("swliod_bad");
  std::ofstream(dir / "bad.yaml") << "config_version: 1\nlidar:\n  msop_port: x\n";
  const pid_t pid = Spawn({Swliod(), "--config", (dir / "bad.yaml").string()}, dir / "out");
  EXPECT_EQ(WaitExit(pid), 78);
  EXPECT_THAT(ReadAll(dir / "out"), HasSubstr("bad.yaml:3:"));
}

TEST(SwliodCommand, RunsUntilSigtermAndStopsCleanly) {
  const auto dir = test::MakeTempDir("swliod_run");
  std::ofstream(dir / "swlio.yaml") << QuietConfig(dir, 154);
  EXPECT_EQ(RunFor(dir, 1500), 0) << ReadAll(dir / "out");
  const std::string log = ReadAll(dir / "log" / "swliod.log");
  EXPECT_THAT(log, HasSubstr("started: lidar rs16"));
  EXPECT_THAT(log, HasSubstr("status initializing"));  // no sensor: never ready
  EXPECT_THAT(log, HasSubstr("stopping (Terminated)"));
  EXPECT_THAT(log, HasSubstr("final status"));
}

// The time offset kept by an earlier run starts the estimator (daemon/state/); a run that
// estimated nothing leaves the file as it was.
TEST(SwliodCommand, StartsFromTheTimeOffsetKeptByTheLastRun) {
  const auto dir = test::MakeTempDir("swliod_state");
  const std::string kept =
      "format: swlio-time-offset 1\noffset_s: -0.00725\nsigma_s: 9e-05\nupdates: 12\n"
      "saved_utc: \"2026-12-05T22:10:00Z\"\n";
  std::ofstream(dir / "time_offset.yaml") << kept;
  // Relative: from the configuration file's directory.
  std::ofstream(dir / "swlio.yaml")
      << QuietConfig(dir, 167) << "state:\n  time_offset_file: time_offset.yaml\n";
  EXPECT_EQ(RunFor(dir, 1000), 0) << ReadAll(dir / "out");
  const std::string log = ReadAll(dir / "log" / "swliod.log");
  EXPECT_THAT(log, HasSubstr("time offset: starting from -7.250 ms (σ 0.090 ms, saved "
                             "2026-12-05T22:10:00Z) in " +
                             (dir / "time_offset.yaml").string()));
  EXPECT_EQ(ReadAll(dir / "time_offset.yaml"), kept);

  std::ofstream(dir / "time_offset.yaml") << "format: swlio-time-offset 1\n";  // damaged
  EXPECT_EQ(RunFor(dir, 1000), 0) << ReadAll(dir / "out");
  EXPECT_THAT(ReadAll(dir / "log" / "swliod.log"),
              HasSubstr("time_offset.yaml: offset_s: missing, or not a number; starting from "
                        "0.00 ms"));
}

TEST(SwliodCommand, PrintedConfigurationPassesCheckConfigOnStdin) {
  const std::string swliod = Swliod();
  const std::string shipped = (test::SourceDir() / "config" / "swlio.yaml").string();
  int code = -1;
  const std::string out = test::RunCommand(
      swliod + " --print-config " + shipped + " | " + swliod + " --check-config - 2>&1", &code);
  EXPECT_EQ(code, 0) << out;
  EXPECT_EQ(out, "<stdin>: OK\n");
  // What it prints is the library's PrintConfig of the file, and nothing else.
  const std::string printed = test::RunCommand(swliod + " --print-config " + shipped, &code);
  EXPECT_EQ(code, 0);
  EXPECT_EQ(printed, PrintConfig(LoadConfigFile(shipped).config));
}

// Standard input has no directory of its own: its relative paths resolve against the current
// one, and --print-config writes them absolute, so the printed file checks from anywhere.
TEST(SwliodCommand, StdinResolvesRelativePathsAgainstTheCurrentDirectory) {
  const std::string swliod = Swliod();
  const auto dir = std::filesystem::canonical(test::MakeTempDir("swliod_stdin"));
  const auto xml = dir / "cyclonedds-loopback.xml";
  std::filesystem::copy_file(test::SourceDir() / "config" / "cyclonedds-loopback.xml", xml);
  int code = -1;
  const std::string printed = test::RunCommand(
      "cd " + dir.string() + " && printf 'config_version: 1\\n' | " + swliod + " --print-config -",
      &code);
  ASSERT_EQ(code, 0) << printed;
  EXPECT_THAT(printed, HasSubstr("  dds_config_file: " + xml.string() + "\n"));
  DaemonConfig defaults;  // a minimal file: every default filled in
  defaults.ipc.dds_config_file = xml.string();
  EXPECT_EQ(printed, PrintConfig(defaults));
  std::ofstream(dir / "printed.yaml") << printed;
  const std::string out = test::RunCommand(
      "cd / && " + swliod + " --check-config - < " + (dir / "printed.yaml").string() + " 2>&1",
      &code);
  EXPECT_EQ(code, 0) << out;
  // The minimal file itself, from elsewhere, does not find the XML.
  test::RunCommand(
      "cd / && printf 'config_version: 1\\n' | " + swliod + " --check-config - 2>/dev/null", &code);
  EXPECT_EQ(code, 1);
}

TEST(SwliodCommand, ARemovedKeyIsRefusedNamingItsReplacement) {
  const std::string swliod = Swliod();
  const std::string old_file = "printf 'config_version: 1\\nestimator:\\n  window_size: 10\\n'";
  int code = -1;
  const std::string out =
      test::RunCommand(old_file + " | " + swliod + " --check-config - 2>&1", &code);
  EXPECT_EQ(code, 1);
  EXPECT_THAT(out, HasSubstr("<stdin>:3:3: estimator.window_size: removed key (it was never "
                             "read); use estimator.window.window_size instead\n"));
  EXPECT_THAT(out, HasSubstr("<stdin>: 1 error(s)"));
  // --print-config refuses it as well, and prints nothing.
  const std::string printed =
      test::RunCommand(old_file + " | " + swliod + " --print-config - 2>/dev/null", &code);
  EXPECT_EQ(code, 1);
  EXPECT_EQ(printed, "");
}

}  // namespace
}  // namespace swlio::daemon

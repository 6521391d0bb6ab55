// swliod as systemd runs it: a bad configuration exits with EX_CONFIG (not restarted), a good
// one runs until SIGTERM and stops cleanly with its status in the log.

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

TEST(SwliodCommand, ABadConfigurationExitsWithExConfig) {
  const auto dir = test::MakeTempDir("swliod_bad");
  std::ofstream(dir / "bad.yaml") << "config_version: 1\nlidar:\n  msop_port: x\n";
  const pid_t pid = Spawn({SWLIOD_PATH, "--config", (dir / "bad.yaml").string()}, dir / "out");
  EXPECT_EQ(WaitExit(pid), 78);
  EXPECT_THAT(ReadAll(dir / "out"), HasSubstr("bad.yaml:3:"));
}

TEST(SwliodCommand, RunsUntilSigtermAndStopsCleanly) {
  const auto dir = test::MakeTempDir("swliod_run");
  std::ofstream(dir / "swlio.yaml")
      << "config_version: 1\nlidar:\n  bind_address: 127.0.0.1\n  msop_port: "
      << test::QuietUdpPort() << "\n  difop_port: " << test::QuietUdpPort()
      << "\nimu:\n  device: " << (dir / "absent-tty").string()
      << "\n  configure_on_start: false\nipc:\n  dds_config_file: "
      << (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string()
      << "\n  domain_id: 154\nlogging:\n  directory: " << (dir / "log").string()
      << "\n  status_period_s: 0.5\n";
  const pid_t pid = Spawn({SWLIOD_PATH, "--config", (dir / "swlio.yaml").string()}, dir / "out");
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  kill(pid, SIGTERM);
  EXPECT_EQ(WaitExit(pid), 0) << ReadAll(dir / "out");
  const std::string log = ReadAll(dir / "log" / "swliod.log");
  EXPECT_THAT(log, HasSubstr("started: lidar rs16"));
  EXPECT_THAT(log, HasSubstr("status initializing"));  // no sensor: never ready
  EXPECT_THAT(log, HasSubstr("stopping (Terminated)"));
  EXPECT_THAT(log, HasSubstr("final status"));
}

}  // namespace
}  // namespace swlio::daemon

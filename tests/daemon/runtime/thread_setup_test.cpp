// The `realtime` configuration section: loading, validation, and applying it to a thread.

#include "swlio/daemon/runtime/thread_setup.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include <thread>

#include "swlio/daemon/config/config_loader.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;

TEST(RealtimeConfig, LoadsThreadsAndReportsBadEntriesWithTheirLine) {
  const LoadedConfig ok = LoadConfigText(
      "config_version: 1\nrealtime:\n  enabled: true\n  lock_memory: true\n  threads:\n"
      "    - {name: imu_rx, priority: 80, cpu: 1}\n    - {name: optimizer}\n",
      "t.yaml", "/etc/swlio");
  ASSERT_TRUE(ok.ok()) << ok.ErrorReport();
  ASSERT_EQ(ok.config.realtime.threads.size(), 2u);
  EXPECT_TRUE(ok.config.realtime.enabled);
  EXPECT_TRUE(ok.config.realtime.lock_memory);
  EXPECT_EQ(ok.config.realtime.threads[0].priority, 80);
  EXPECT_EQ(ok.config.realtime.threads[0].cpu, 1);
  EXPECT_EQ(ok.config.realtime.threads[1].priority, 0);

  const LoadedConfig bad = LoadConfigText(
      "config_version: 1\nrealtime:\n  threads:\n    - {name: lidar, priority: 120, cpus: 2}\n",
      "t.yaml", "/etc/swlio");
  const std::string report = bad.ErrorReport();
  EXPECT_THAT(report, HasSubstr("realtime.threads[0].name"));
  EXPECT_THAT(report, HasSubstr("realtime.threads[0].priority"));
  EXPECT_THAT(report, HasSubstr("cpus"));  // unknown key
  EXPECT_THAT(report, HasSubstr("t.yaml:4"));
}

TEST(RealtimeConfig, MaxSweepLagDefaultsOnAndIsRangeChecked) {
  EXPECT_EQ(RealtimeConfig{}.max_sweep_lag_s, 0.5);
  const LoadedConfig off = LoadConfigText("config_version: 1\nrealtime:\n  max_sweep_lag_s: 0\n",
                                          "t.yaml", "/etc/swlio");
  ASSERT_TRUE(off.ok()) << off.ErrorReport();
  EXPECT_EQ(off.config.realtime.max_sweep_lag_s, 0.0);
  const LoadedConfig bad = LoadConfigText("config_version: 1\nrealtime:\n  max_sweep_lag_s: -1\n",
                                          "t.yaml", "/etc/swlio");
  EXPECT_THAT(bad.ErrorReport(), HasSubstr("realtime.max_sweep_lag_s"));
}

TEST(ThreadSetup, PinsTheThreadAndReportsWhatItCannotApply) {
  RealtimeConfig config;
  config.enabled = true;
  config.threads = {{"imu_rx", 0, 0}, {"publisher", 0, 1023}};
  std::vector<std::string> pinned_problems, bad_problems;
  cpu_set_t pinned;
  CPU_ZERO(&pinned);
  std::thread a([&] {
    pinned_problems = SetUpThisThread("imu_rx", config);
    pthread_getaffinity_np(pthread_self(), sizeof pinned, &pinned);
  });
  a.join();
  EXPECT_TRUE(pinned_problems.empty());
  EXPECT_EQ(CPU_COUNT(&pinned), 1);
  EXPECT_TRUE(CPU_ISSET(0, &pinned));
  std::thread b([&] { bad_problems = SetUpThisThread("publisher", config); });
  b.join();
  ASSERT_EQ(bad_problems.size(), 1u);
  EXPECT_THAT(bad_problems[0], HasSubstr("publisher: pinning to CPU 1023 failed"));
  config.enabled = false;
  std::thread c([&] { EXPECT_TRUE(SetUpThisThread("publisher", config).empty()); });
  c.join();
}

TEST(ThreadSetup, SetsTheNiceValueOfThisThreadOnlyEvenWithoutRealtime) {
  // Relative to the nice value the tests run under (CI may run them under `nice`), and raised,
  // which needs no privilege.
  errno = 0;
  const int inherited = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
  const int target = std::min(inherited + 5, 19);
  if (target == inherited) GTEST_SKIP() << "the tests run at nice 19: no higher value to set";
  RealtimeConfig config;  // enabled: false
  config.threads = {{"optimizer", 0, -1, target}};
  int nice = 0;
  std::vector<std::string> problems;
  std::thread t([&] {
    problems = SetUpThisThread("optimizer", config);
    errno = 0;
    nice = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
  });
  t.join();
  EXPECT_TRUE(problems.empty());
  EXPECT_EQ(nice, target);
  EXPECT_EQ(getpriority(PRIO_PROCESS, static_cast<id_t>(gettid())), inherited)
      << "other threads keep theirs";
}

// What the child of RunUnprivileged found, as its exit status.
enum Outcome : int { kFifo = 10, kNiceFallback = 11, kNeither = 12, kCannotRaiseLimit = 13 };

// Forks; the child sets RLIMIT_RTPRIO (swliod.service: LimitRTPRIO), becomes an unprivileged
// user (no capabilities left, as swliod under its unit), applies the schedule
// `imu_rx: FIFO 70, nice 5` to its only thread and exits with what it got. (Nice 5, not the
// daemon's -10: raising the nice value needs no RLIMIT_NICE.)
int RunUnprivileged(rlim_t rtprio) {
  const pid_t pid = fork();
  if (pid == 0) {
    const rlimit rt_limit{rtprio, rtprio};
    if (setrlimit(RLIMIT_RTPRIO, &rt_limit) != 0) _exit(kCannotRaiseLimit);
    if (setresgid(65534, 65534, 65534) != 0 || setresuid(65534, 65534, 65534) != 0) _exit(1);
    RealtimeConfig config;
    config.enabled = true;
    config.threads = {{"imu_rx", 70, -1, 5}};
    const std::vector<std::string> problems = SetUpThisThread("imu_rx", config);
    if (sched_getscheduler(0) == SCHED_FIFO && problems.empty()) _exit(kFifo);
    const bool said = problems.size() == 1 &&
                      problems[0].find("SCHED_FIFO 70 failed") != std::string::npos &&
                      problems[0].find("nice 5 instead") != std::string::npos;
    errno = 0;
    const int nice = getpriority(PRIO_PROCESS, 0);
    _exit(said && sched_getscheduler(0) == SCHED_OTHER && nice == 5 ? kNiceFallback : kNeither);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// swliod.service gives the daemon no capability: where RLIMIT_RTPRIO forbids SCHED_FIFO, the
// thread keeps its nice value instead of running at 0.
TEST(ThreadSetup, WithoutTheRtprioLimitTheThreadKeepsItsNiceValue) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to become an unprivileged user with limits";
  EXPECT_EQ(RunUnprivileged(0), kNiceFallback);
}

// ... and SCHED_FIFO comes from LimitRTPRIO alone.
TEST(ThreadSetup, FifoNeedsOnlyTheRtprioLimit) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to become an unprivileged user with limits";
  const int outcome = RunUnprivileged(80);
  if (outcome == kCannotRaiseLimit) {
    GTEST_SKIP() << "this process cannot raise RLIMIT_RTPRIO to 80 (no CAP_SYS_RESOURCE and a "
                    "lower hard limit), as systemd does for the unit";
  }
  EXPECT_EQ(outcome, kFifo);
}

TEST(RealtimeConfig, NiceIsLoadedAndBounded) {
  const LoadedConfig ok =
      LoadConfigText("config_version: 1\nrealtime:\n  threads:\n    - {name: imu_rx, nice: -10}\n",
                     "t.yaml", "/etc/swlio");
  ASSERT_TRUE(ok.ok()) << ok.ErrorReport();
  EXPECT_EQ(ok.config.realtime.threads[0].nice, -10);
  const LoadedConfig bad =
      LoadConfigText("config_version: 1\nrealtime:\n  threads:\n    - {name: imu_rx, nice: -21}\n",
                     "t.yaml", "/etc/swlio");
  EXPECT_THAT(bad.ErrorReport(), HasSubstr("realtime.threads[0].nice"));
}

}  // namespace
}  // namespace swlio::daemon

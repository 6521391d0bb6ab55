#include "swlio/daemon/runtime/watchdog.h"

#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "swlio/core/time.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

/// A clock the test moves by hand.
struct FakeClock {
  int64_t now_ns = 1'000 * kNsPerSec;
  Watchdog::Clock Fn() {
    return [this] { return now_ns; };
  }
};

/// Records every message instead of talking to systemd.
class RecordingSink final : public NotifySink {
 public:
  bool Send(std::string_view message) override {
    messages.emplace_back(message);
    return deliver;
  }
  size_t Count(std::string_view message) const {
    size_t n = 0;
    for (const auto& m : messages) n += (m == message) ? 1 : 0;
    return n;
  }
  std::vector<std::string> messages;
  bool deliver = true;
};

TEST(Watchdog, HealthyWhileEveryThreadBeats) {
  FakeClock clock;
  Watchdog wd(2 * kNsPerSec, clock.Fn());
  const auto lidar = wd.Register("lidar_rx");
  const auto imu = wd.Register("imu_rx");
  for (int i = 0; i < 10; ++i) {
    clock.now_ns += kNsPerSec;
    lidar.Beat();
    imu.Beat();
    const Watchdog::Report r = wd.Check();
    EXPECT_TRUE(r.healthy) << "step " << i;
    EXPECT_TRUE(r.stalled.empty());
  }
  EXPECT_EQ(wd.thread_count(), 2u);
}

TEST(Watchdog, NamesTheThreadThatStopped) {
  FakeClock clock;
  Watchdog wd(2 * kNsPerSec, clock.Fn());
  const auto lidar = wd.Register("lidar_rx");
  const auto optimizer = wd.Register("optimizer");
  (void)optimizer;                // registered, then never beats again
  clock.now_ns += 2 * kNsPerSec;  // exactly the timeout: not yet stalled
  lidar.Beat();
  EXPECT_TRUE(wd.Check().healthy);
  clock.now_ns += 1;
  lidar.Beat();
  const Watchdog::Report r = wd.Check();
  EXPECT_FALSE(r.healthy);
  ASSERT_EQ(r.stalled.size(), 1u);
  EXPECT_EQ(r.stalled[0], "optimizer");
  EXPECT_EQ(r.worst_silence_ns, 2 * kNsPerSec + 1);
}

TEST(Watchdog, RecoversWhenTheThreadBeatsAgain) {
  FakeClock clock;
  Watchdog wd(kNsPerSec, clock.Fn());
  const auto t = wd.Register("propagator");
  clock.now_ns += 3 * kNsPerSec;
  EXPECT_FALSE(wd.Check().healthy);
  t.Beat();
  EXPECT_TRUE(wd.Check().healthy);
}

TEST(Watchdog, EmptyIsHealthyAndDefaultHandleIsInert) {
  FakeClock clock;
  Watchdog wd(kNsPerSec, clock.Fn());
  EXPECT_TRUE(wd.Check().healthy);
  Watchdog::Handle nothing;
  nothing.Beat();  // must not crash
  EXPECT_EQ(wd.thread_count(), 0u);
}

TEST(Watchdog, RejectsNonPositiveTimeout) {
  EXPECT_THROW(Watchdog(0), std::invalid_argument);
  EXPECT_THROW(Watchdog(-5), std::invalid_argument);
}

TEST(Watchdog, BeatsFromManyThreadsAreSeen) {
  Watchdog wd(60 * kNsPerSec);  // real monotonic clock
  std::vector<Watchdog::Handle> handles;
  for (const char* name : {"lidar_rx", "imu_rx", "propagator", "optimizer"}) {
    handles.push_back(wd.Register(name));
  }
  std::vector<std::thread> threads;
  for (const auto& h : handles) {
    threads.emplace_back([h] {
      for (int k = 0; k < 1000; ++k) h.Beat();
    });
  }
  for (auto& t : threads) t.join();
  const Watchdog::Report r = wd.Check();
  EXPECT_TRUE(r.healthy);
  EXPECT_GE(r.worst_silence_ns, 0);
}

TEST(SystemdNotifier, ReadyStatusStoppingMessages) {
  RecordingSink sink;
  SystemdNotifier n(&sink, nullptr, 0);
  EXPECT_TRUE(n.Ready("streaming: lidar 10 Hz, imu 400 Hz"));
  EXPECT_TRUE(n.Status("two\nlines"));
  EXPECT_TRUE(n.Stopping("SIGTERM"));
  ASSERT_EQ(sink.messages.size(), 3u);
  EXPECT_EQ(sink.messages[0], "READY=1\nSTATUS=streaming: lidar 10 Hz, imu 400 Hz");
  EXPECT_EQ(sink.messages[1], "STATUS=two lines");
  EXPECT_EQ(sink.messages[2], "STOPPING=1\nSTATUS=SIGTERM");
}

TEST(SystemdNotifier, PingsAtHalfTheIntervalWhileHealthy) {
  FakeClock clock;
  Watchdog wd(5 * kNsPerSec, clock.Fn());
  const auto t = wd.Register("imu_rx");
  RecordingSink sink;
  SystemdNotifier n(&sink, &wd, 5 * kNsPerSec);
  EXPECT_EQ(n.ping_period_ns(), 2500 * kNsPerMs);
  // 10 s of ticks every 100 ms: the first tick pings, then one ping per 2.5 s.
  for (int i = 0; i <= 100; ++i) {
    t.Beat();
    n.Tick(clock.now_ns);
    clock.now_ns += 100 * kNsPerMs;
  }
  EXPECT_EQ(sink.Count("WATCHDOG=1"), 5u);  // at 0, 2.5, 5, 7.5, 10 s
  EXPECT_EQ(n.pings_sent(), 5u);
  EXPECT_EQ(n.pings_withheld(), 0u);
}

TEST(SystemdNotifier, WithholdsPingsWhileAThreadIsStalled) {
  FakeClock clock;
  Watchdog wd(2 * kNsPerSec, clock.Fn());
  const auto lidar = wd.Register("lidar_rx");
  const auto optimizer = wd.Register("optimizer");
  RecordingSink sink;
  SystemdNotifier n(&sink, &wd, 4 * kNsPerSec);
  n.Tick(clock.now_ns);
  ASSERT_EQ(n.pings_sent(), 1u);
  // The optimizer hangs; lidar keeps going for 10 s.
  for (int i = 0; i < 100; ++i) {
    clock.now_ns += 100 * kNsPerMs;
    lidar.Beat();
    n.Tick(clock.now_ns);
  }
  // Only the ping at 2 s (optimizer silent 2 s, not more) may follow the first one.
  EXPECT_EQ(n.pings_sent(), 2u);
  EXPECT_GT(n.pings_withheld(), 0u);
  size_t stall_status = 0;
  for (const auto& m : sink.messages) {
    if (m == "STATUS=watchdog withheld: no progress from optimizer") ++stall_status;
  }
  EXPECT_EQ(stall_status, 1u);  // reported once per episode, not per tick
  // The optimizer resumes: pings resume at the next tick.
  optimizer.Beat();
  clock.now_ns += 100 * kNsPerMs;
  lidar.Beat();
  EXPECT_TRUE(n.Tick(clock.now_ns).healthy);
  EXPECT_EQ(n.pings_sent(), 3u);
}

TEST(SystemdNotifier, NoPingsWhenTheWatchdogIsOff) {
  FakeClock clock;
  Watchdog wd(kNsPerSec, clock.Fn());
  RecordingSink sink;
  SystemdNotifier n(&sink, &wd, 0);
  for (int i = 0; i < 10; ++i) n.Tick(clock.now_ns += kNsPerSec);
  EXPECT_EQ(sink.Count("WATCHDOG=1"), 0u);
  EXPECT_EQ(n.ping_period_ns(), 0);
}

TEST(SystemdNotifier, FailedSendIsRetriedAtTheNextTick) {
  FakeClock clock;
  Watchdog wd(kNsPerSec, clock.Fn());
  RecordingSink sink;
  sink.deliver = false;
  SystemdNotifier n(&sink, &wd, 2 * kNsPerSec);
  n.Tick(clock.now_ns);
  EXPECT_EQ(n.pings_sent(), 0u);
  sink.deliver = true;
  n.Tick(clock.now_ns += 1);
  EXPECT_EQ(n.pings_sent(), 1u);
}

TEST(SystemdWatchdogInterval, ReadsWatchdogUsecForThisProcess) {
  // sd_watchdog_enabled checks WATCHDOG_PID against getpid(); set both, then restore.
  const std::string pid = std::to_string(getpid());
  ASSERT_EQ(setenv("WATCHDOG_USEC", "5000000", 1), 0);
  ASSERT_EQ(setenv("WATCHDOG_PID", pid.c_str(), 1), 0);
  EXPECT_EQ(SystemdWatchdogIntervalNs(), 5 * kNsPerSec);
  ASSERT_EQ(setenv("WATCHDOG_PID", "1", 1), 0);  // another process's watchdog
  EXPECT_EQ(SystemdWatchdogIntervalNs(), 0);
  unsetenv("WATCHDOG_USEC");
  unsetenv("WATCHDOG_PID");
  EXPECT_EQ(SystemdWatchdogIntervalNs(), 0);
}

TEST(SdNotifySink, NoSocketIsNotAnError) {
  unsetenv("NOTIFY_SOCKET");
  SdNotifySink sink;
  EXPECT_TRUE(sink.Send("STATUS=test"));
}

TEST(SdNotifySink, DeliversToTheNotifySocket) {
  // Play the service manager: a datagram socket named by NOTIFY_SOCKET, as systemd provides.
  const std::string path = (test::MakeTempDir("notify") / "notify.sock").string();
  const int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  ASSERT_LT(path.size(), sizeof(addr.sun_path));
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)), 0);
  ASSERT_EQ(setenv("NOTIFY_SOCKET", path.c_str(), 1), 0);
  SdNotifySink sink;
  SystemdNotifier notifier(&sink, nullptr, 0);
  EXPECT_TRUE(notifier.Ready("initialized"));
  unsetenv("NOTIFY_SOCKET");
  char buffer[256] = {};
  const ssize_t n = recv(fd, buffer, sizeof(buffer) - 1, MSG_DONTWAIT);
  close(fd);
  ASSERT_GT(n, 0);
  EXPECT_EQ(std::string(buffer, static_cast<size_t>(n)), "READY=1\nSTATUS=initialized");
}

}  // namespace
}  // namespace swlio::daemon

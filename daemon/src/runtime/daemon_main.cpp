#include "swlio/daemon/runtime/daemon_main.h"

#include <signal.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <ctime>
#include <string>

#include "swlio/daemon/runtime/thread_setup.h"
#include "swlio/daemon/runtime/watchdog.h"

namespace swlio::daemon {
namespace {

sigset_t StopSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGHUP);
  return set;
}

/// Waits up to 100 ms for a stop signal; its number, or 0.
int WaitForStopSignal() {
  const sigset_t set = StopSignals();
  const timespec timeout{0, 100'000'000};
  const int sig = sigtimedwait(&set, nullptr, &timeout);
  return sig > 0 ? sig : 0;
}

/// The estimator fell behind and shed sweeps: the CPU it gets does not suffice.
void LogCpuDegraded(const HealthRates& rates) {
  if (rates.sweeps_skipped_behind == 0) return;
  spdlog::warn(
      "degraded: CPU: {} sweeps skipped since the last status (the estimator fell behind the "
      "LiDAR); the IMU-rate pose continues. A busy computer or a CPU quota: docs/scheduling.md",
      rates.sweeps_skipped_behind);
}

void LogDrops(const HealthSnapshot& s) {
  for (const QueueCounters& q : s.queues) {
    if (q.dropped > 0) {
      spdlog::warn("queue {} ({} -> {}): {} dropped, high water {}/{}", q.name, q.producer,
                   q.consumer, q.dropped, q.high_water, q.capacity);
    }
  }
}

}  // namespace

void BlockStopSignals() {
  const sigset_t set = StopSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

int RunDaemon(const DaemonConfig& config, const RuntimeOptions& options, int64_t max_run_ns) {
  std::string error;
  std::unique_ptr<Runtime> rt = Runtime::Create(config, options, &error);
  if (!rt) {
    spdlog::critical("start-up failed: {}", error);
    return 1;
  }
  SdNotifySink sink;
  SystemdNotifier notifier(&sink, &rt->watchdog(), SystemdWatchdogIntervalNs());
  rt->Start();
  if (const std::string problem = LockMemory(config.realtime); !problem.empty()) {
    spdlog::warn("realtime: {}", problem);
  }
  spdlog::info("started: lidar {} on UDP {} (MSOP) / {} (DIFOP), imu {} at {} baud, mode {}",
               config.lidar.model, rt->msop_port(), config.lidar.difop_port, config.imu.device,
               config.imu.baud, config.estimator.mode);
  notifier.Status("waiting for sensors and initialization");
  const int64_t start_ns = MonotonicNowNs();
  const auto status_period_ns = static_cast<int64_t>(config.logging.status_period_s * 1e9);
  int64_t next_status_ns = start_ns + status_period_ns;
  int64_t next_record_ns = start_ns + 1'000'000'000;  // health.csv rows and incident events
  HealthReporter logged;
  bool ready = false;
  int signal = 0;
  while ((signal = WaitForStopSignal()) == 0) {
    const int64_t now = MonotonicNowNs();
    const Watchdog::Report watchdog = notifier.Tick(now);
    if (now >= next_record_ns) {
      next_record_ns = now + 1'000'000'000;
      rt->ObserveForRecording(watchdog.stalled);
    }
    if (!ready && rt->Ready()) {
      ready = true;
      notifier.Ready("tracking");
      spdlog::info("ready: sensors streaming, estimator initialized after {:.1f} s",
                   static_cast<double>(now - start_ns) * 1e-9);
    }
    if (now >= next_status_ns) {
      next_status_ns = now + status_period_ns;
      const HealthSnapshot s = rt->Snapshot();
      const HealthRates rates = logged.Rates(s);
      const std::string line = StatusLine(s, rates);
      spdlog::info("{}", line);
      notifier.Status(line);
      LogDrops(s);
      for (const std::string& w : ClockJumpWarnings(s, rates)) spdlog::warn("{}", w);
      LogCpuDegraded(rates);
    }
    if (max_run_ns > 0 && now - start_ns >= max_run_ns) break;
  }
  notifier.Stopping(signal != 0 ? "stopping on signal " + std::to_string(signal)
                                : "stopping: run time limit");
  spdlog::info("stopping ({})", signal != 0 ? strsignal(signal) : "run time limit");
  rt->Stop();
  const HealthSnapshot s = rt->Snapshot();
  const HealthRates rates = logged.Rates(s);
  spdlog::info("final {}", StatusLine(s, rates));
  LogDrops(s);
  for (const std::string& w : ClockJumpWarnings(s, rates)) spdlog::warn("{}", w);
  return 0;
}

}  // namespace swlio::daemon

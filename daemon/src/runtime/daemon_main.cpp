#include "swlio/daemon/runtime/daemon_main.h"

#include <signal.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <ctime>
#include <string>

#include "swlio/core/time.h"
#include "swlio/daemon/runtime/event_log.h"
#include "swlio/daemon/runtime/health_events.h"
#include "swlio/daemon/runtime/thread_setup.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/daemon/state/time_offset_keeper.h"

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

}  // namespace

void BlockStopSignals() {
  const sigset_t set = StopSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

int RunDaemon(const DaemonConfig& file_config, const RuntimeOptions& options, int64_t max_run_ns) {
  DaemonConfig config = file_config;
  TimeOffsetKeeper time_offset(config.state.time_offset_file, SecToNs(config.state.save_period_s));
  time_offset.Apply(&config.window.time_offset);
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
  LogEvent(
      spdlog::level::info, "started",
      fmt::format("started: lidar {} on UDP {} (MSOP) / {} (DIFOP), imu {} at {} baud, mode {}",
                  config.lidar.model, rt->msop_port(), config.lidar.difop_port, config.imu.device,
                  config.imu.baud, config.estimator.mode),
      {{"LIDAR_MODEL", config.lidar.model},
       {"MSOP_PORT", std::to_string(rt->msop_port())},
       {"IMU_DEVICE", config.imu.device},
       {"MODE", config.estimator.mode}});
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
      const HealthSnapshot s = rt->Snapshot();
      rt->ObserveForRecording(s, watchdog.stalled);
      time_offset.Observe(s.optimizer.time_offset, now);
    }
    if (!ready && rt->Ready()) {
      ready = true;
      notifier.Ready("tracking");
      const double after_s = static_cast<double>(now - start_ns) * 1e-9;
      LogEvent(
          spdlog::level::info, "ready",
          fmt::format("ready: sensors streaming, estimator initialized after {:.1f} s", after_s),
          {{"AFTER_S", fmt::format("{:.1f}", after_s)}});
    }
    if (now >= next_status_ns) {
      next_status_ns = now + status_period_ns;
      const HealthSnapshot s = rt->Snapshot();
      const HealthRates rates = logged.Rates(s);
      const std::string line = StatusLine(s, rates);
      notifier.Status(line);
      LogHealthEvents(StatusEvents(s, rates, line));
    }
    if (max_run_ns > 0 && now - start_ns >= max_run_ns) break;
  }
  notifier.Stopping(signal != 0 ? "stopping on signal " + std::to_string(signal)
                                : "stopping: run time limit");
  const std::string why = signal != 0 ? strsignal(signal) : "run time limit";
  LogEvent(spdlog::level::info, "stopping", "stopping (" + why + ")", {{"REASON", why}});
  rt->Stop();
  const HealthSnapshot s = rt->Snapshot();
  time_offset.Flush(s.optimizer.time_offset);
  const HealthRates rates = logged.Rates(s);
  std::vector<HealthEvent> final_events = StatusEvents(s, rates, "final " + StatusLine(s, rates));
  final_events.front().fields.push_back({"FINAL", "1"});
  LogHealthEvents(final_events);
  return 0;
}

}  // namespace swlio::daemon

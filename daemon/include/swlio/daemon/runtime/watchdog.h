#pragma once
/// @file
/// Liveness for systemd: a per-thread progress Watchdog and the sd_notify messages the daemon
/// sends (READY=1, STATUS=, WATCHDOG=1, STOPPING=1).
///
/// Protocol (sd_notify(3), sd_watchdog_enabled(3), systemd.service(5) WatchdogSec=): with
/// Type=notify the service manager waits for "READY=1" before it calls the unit started; with
/// WatchdogSec=T it exports WATCHDOG_USEC=T (and WATCHDOG_PID) and kills the service with
/// SIGABRT when no "WATCHDOG=1" arrives for T after start-up. sd_notify(3) recommends pinging
/// every T/2. Without NOTIFY_SOCKET (not under systemd) every message is silently dropped.
///
/// The rule: WATCHDOG=1 is sent only while every registered thread has reported progress
/// within the stall timeout, so a thread stuck in a loop or a deadlock stops the pings and
/// systemd restarts the daemon (Restart=on-failure).

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace swlio::daemon {

/// Where notification messages go: sd_notify in the daemon, a recorder in tests.
class NotifySink {
 public:
  virtual ~NotifySink() = default;
  /// Sends one newline-separated "KEY=value" message; false when it could not be delivered.
  virtual bool Send(std::string_view message) = 0;
};

/// The real sink: sd_notify(0, message). Returns true also when not running under systemd
/// (sd_notify returns 0 then: nothing to deliver is not an error).
class SdNotifySink final : public NotifySink {
 public:
  bool Send(std::string_view message) override;
};

/// The watchdog interval systemd asks for (WATCHDOG_USEC, checked against WATCHDOG_PID via
/// sd_watchdog_enabled), in ns; 0 when the watchdog is off or the variables are malformed.
int64_t SystemdWatchdogIntervalNs();

/// CLOCK_MONOTONIC in ns, the clock systemd's watchdog runs on.
int64_t MonotonicNowNs();

/// The calling thread's CPU time in ns (CLOCK_THREAD_CPUTIME_ID): what work took on its core,
/// unaffected by other load; stage timings use it (on an idle core it equals the wall time).
int64_t ThreadCpuNowNs();

/// Per-thread progress tracking. Each long-running thread registers once and calls Beat() on
/// every loop iteration, including the iterations where a blocking read timed out (so an idle
/// but healthy thread keeps beating; a thread blocked forever does not).
///
/// Thread roles: Register() and Check() take a mutex (start-up and the notifier thread);
/// Handle::Beat() is one clock read and one relaxed atomic store, safe from any thread and free
/// of allocation.
class Watchdog {
 public:
  using Clock = std::function<int64_t()>;  ///< monotonic ns

  /// A thread's reporting handle. Cheap to copy; valid while the Watchdog lives.
  class Handle {
   public:
    Handle() = default;
    /// Records progress now. A default-constructed handle ignores beats.
    void Beat() const;

   private:
    friend class Watchdog;
    struct Slot;
    Handle(const Watchdog* owner, Slot* slot) : owner_(owner), slot_(slot) {}
    const Watchdog* owner_ = nullptr;
    Slot* slot_ = nullptr;
  };

  /// Outcome of one Check().
  struct Report {
    bool healthy = true;               ///< every thread beat within the stall timeout
    std::vector<std::string> stalled;  ///< names of the threads that did not
    int64_t worst_silence_ns = 0;      ///< longest time since any thread's last beat
  };

  /// @param stall_timeout_ns a thread whose last beat is older than this is stalled (> 0).
  ///        Use at most the systemd watchdog interval W: pings stop at most this long after a
  ///        thread hangs, and systemd acts W after the last ping, so a hang is caught within
  ///        stall_timeout_ns + W.
  /// @param clock monotonic ns source; MonotonicNowNs when empty.
  explicit Watchdog(int64_t stall_timeout_ns, Clock clock = {});
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  /// Adds a thread. Registration counts as its first beat (start-up grace of one timeout).
  Handle Register(std::string name);

  /// Whether every registered thread progressed within the stall timeout. With no thread
  /// registered the report is healthy (only the calling thread exists, and it is running).
  Report Check() const;

  int64_t stall_timeout_ns() const { return stall_timeout_ns_; }
  size_t thread_count() const;

 private:
  int64_t Now() const { return clock_(); }

  const int64_t stall_timeout_ns_;
  const Clock clock_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Handle::Slot>> slots_;  // stable addresses for handles
};

/// The daemon's side of the sd_notify protocol. Owned and called by one thread (the main
/// thread's supervision loop); Tick() is cheap and is meant to be called at least every
/// ping_period_ns().
class SystemdNotifier {
 public:
  /// @param watchdog_interval_ns systemd's WatchdogSec in ns (SystemdWatchdogIntervalNs()),
  ///        0 when the watchdog is off: Tick() then never pings.
  SystemdNotifier(NotifySink* sink, const Watchdog* watchdog, int64_t watchdog_interval_ns);

  /// "READY=1" plus a STATUS line. Call once sensors stream and the estimator is initialized.
  bool Ready(std::string_view status);
  /// "STATUS=<text>" (newlines are replaced: one status line).
  bool Status(std::string_view status);
  /// "STOPPING=1" plus a STATUS line, when shutdown begins.
  bool Stopping(std::string_view status);

  /// Sends "WATCHDOG=1" when the watchdog is enabled, ping_period_ns() has passed since the
  /// last ping, and every registered thread is healthy. When a thread is stalled it sends no
  /// ping and, once per stall episode, a STATUS naming the stalled threads. Returns the report.
  Watchdog::Report Tick(int64_t now_ns);

  /// Half the watchdog interval, as sd_notify(3) recommends; 0 when the watchdog is off.
  int64_t ping_period_ns() const { return watchdog_interval_ns_ / 2; }
  uint64_t pings_sent() const { return pings_sent_; }
  uint64_t pings_withheld() const { return pings_withheld_; }

 private:
  NotifySink* sink_;
  const Watchdog* watchdog_;
  const int64_t watchdog_interval_ns_;
  int64_t last_ping_ns_ = 0;
  bool pinged_once_ = false;
  bool stall_reported_ = false;
  uint64_t pings_sent_ = 0;
  uint64_t pings_withheld_ = 0;
};

}  // namespace swlio::daemon

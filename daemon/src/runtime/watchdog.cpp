#include "swlio/daemon/runtime/watchdog.h"

#include <systemd/sd-daemon.h>
#include <time.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace swlio::daemon {

struct Watchdog::Handle::Slot {
  Slot(std::string n, int64_t t_ns) : name(std::move(n)), last_beat_ns(t_ns) {}
  const std::string name;
  std::atomic<int64_t> last_beat_ns;
};

bool SdNotifySink::Send(std::string_view message) {
  const std::string text(message);  // sd_notify wants a NUL-terminated string
  return sd_notify(0, text.c_str()) >= 0;
}

int64_t SystemdWatchdogIntervalNs() {
  uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) <= 0) return 0;
  constexpr uint64_t kMaxUsec = static_cast<uint64_t>(INT64_MAX / 1000);
  return static_cast<int64_t>(std::min(usec, kMaxUsec)) * 1000;
}

int64_t ThreadCpuNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

int64_t MonotonicNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + static_cast<int64_t>(ts.tv_nsec);
}

void Watchdog::Handle::Beat() const {
  if (slot_ == nullptr) return;
  slot_->last_beat_ns.store(owner_->Now(), std::memory_order_relaxed);
}

Watchdog::Watchdog(int64_t stall_timeout_ns, Clock clock)
    : stall_timeout_ns_(stall_timeout_ns),
      clock_(clock ? std::move(clock) : Clock(&MonotonicNowNs)) {
  if (stall_timeout_ns_ <= 0) throw std::invalid_argument("Watchdog: stall timeout must be > 0");
}

Watchdog::~Watchdog() = default;

Watchdog::Handle Watchdog::Register(std::string name) {
  std::lock_guard<std::mutex> lock(mutex_);
  slots_.push_back(std::make_unique<Handle::Slot>(std::move(name), Now()));
  return Handle(this, slots_.back().get());
}

size_t Watchdog::thread_count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return slots_.size();
}

Watchdog::Report Watchdog::Check() const {
  std::lock_guard<std::mutex> lock(mutex_);
  Report report;
  const int64_t now_ns = Now();
  for (const auto& slot : slots_) {
    const int64_t silence_ns = now_ns - slot->last_beat_ns.load(std::memory_order_relaxed);
    report.worst_silence_ns = std::max(report.worst_silence_ns, silence_ns);
    if (silence_ns > stall_timeout_ns_) {
      report.healthy = false;
      report.stalled.push_back(slot->name);
    }
  }
  return report;
}

namespace {

std::string OneLine(std::string_view text) {
  std::string line(text);
  std::replace(line.begin(), line.end(), '\n', ' ');
  return line;
}

}  // namespace

SystemdNotifier::SystemdNotifier(NotifySink* sink,
                                 const Watchdog* watchdog,
                                 int64_t watchdog_interval_ns)
    : sink_(sink),
      watchdog_(watchdog),
      watchdog_interval_ns_(std::max<int64_t>(0, watchdog_interval_ns)) {}

bool SystemdNotifier::Ready(std::string_view status) {
  return sink_->Send("READY=1\nSTATUS=" + OneLine(status));
}

bool SystemdNotifier::Status(std::string_view status) {
  return sink_->Send("STATUS=" + OneLine(status));
}

bool SystemdNotifier::Stopping(std::string_view status) {
  return sink_->Send("STOPPING=1\nSTATUS=" + OneLine(status));
}

Watchdog::Report SystemdNotifier::Tick(int64_t now_ns) {
  Watchdog::Report report = watchdog_ != nullptr ? watchdog_->Check() : Watchdog::Report{};
  if (!report.healthy) {
    if (!stall_reported_) {
      std::string names;
      for (const auto& name : report.stalled) names += (names.empty() ? "" : ", ") + name;
      Status("watchdog withheld: no progress from " + names);
      stall_reported_ = true;
    }
  } else {
    stall_reported_ = false;
  }
  if (watchdog_interval_ns_ == 0) return report;
  const bool due = !pinged_once_ || now_ns - last_ping_ns_ >= ping_period_ns();
  if (!due) return report;
  if (!report.healthy) {
    ++pings_withheld_;
    return report;
  }
  if (sink_->Send("WATCHDOG=1")) {
    ++pings_sent_;
    last_ping_ns_ = now_ns;
    pinged_once_ = true;
  }
  return report;
}

}  // namespace swlio::daemon

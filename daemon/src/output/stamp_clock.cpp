#include "swlio/daemon/output/stamp_clock.h"

#include <time.h>

#include <cstdlib>
#include <utility>

#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/drivers/rx_timestamp.h"

namespace swlio::daemon {

int64_t RealtimeNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + static_cast<int64_t>(ts.tv_nsec);
}

ClockOffsetSample SampleClockOffset(const ClockSources& clocks) {
  const auto read = [&clocks] {
    drivers::ClockReading r;
    r.mono_before_ns = clocks.monotonic ? clocks.monotonic() : MonotonicNowNs();
    r.real_ns = clocks.realtime ? clocks.realtime() : RealtimeNowNs();
    r.mono_after_ns = clocks.monotonic ? clocks.monotonic() : MonotonicNowNs();
    return r;
  };
  const drivers::ClockReading best =
      drivers::TightestClockReading(read, StampClock::kPairAttempts, StampClock::kMaxPairGapNs);
  return {best.mono_mid_ns(), best.real_ns - best.mono_mid_ns()};
}

StampClock::StampClock(bool realtime, ClockSources clocks)
    : realtime_(realtime), clocks_(std::move(clocks)) {
  const ClockOffsetSample s = SampleClockOffset(clocks_);
  last_t_ns_ = s.t_monotonic_ns;
  offset_ns_.store(s.offset_ns, std::memory_order_relaxed);
}

std::optional<WallClockStep> StampClock::Update() {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  const ClockOffsetSample s = SampleClockOffset(clocks_);
  const int64_t change_ns = s.offset_ns - offset_ns_.load(kRelaxed);
  const double dt_ns = static_cast<double>(s.t_monotonic_ns - last_t_ns_);
  const double slew_ns = kMaxSlewFraction * (dt_ns > 0.0 ? dt_ns : 0.0);
  offset_ns_.store(s.offset_ns, kRelaxed);
  last_t_ns_ = s.t_monotonic_ns;
  if (static_cast<double>(std::llabs(change_ns)) <= static_cast<double>(kStepMinNs) + slew_ns) {
    return std::nullopt;
  }
  steps_.fetch_add(1, kRelaxed);
  last_step_ns_.store(change_ns, kRelaxed);
  last_step_t_ns_.store(s.t_monotonic_ns, kRelaxed);
  return WallClockStep{s.t_monotonic_ns, change_ns, s.offset_ns};
}

StampClockCounters StampClock::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  StampClockCounters c;
  c.realtime = realtime_;
  c.offset_ns = offset_ns_.load(kRelaxed);
  c.steps = steps_.load(kRelaxed);
  c.last_step_ns = last_step_ns_.load(kRelaxed);
  c.last_step_monotonic_ns = last_step_t_ns_.load(kRelaxed);
  return c;
}

}  // namespace swlio::daemon

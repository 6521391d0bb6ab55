#pragma once
/// @file
/// Published stamps in ROS time (issue 34). The daemon's time is CLOCK_MONOTONIC ns, and stays
/// so: the clock models, the estimator and the queues never see the wall clock. ROS 2 nodes
/// stamp and look up in CLOCK_REALTIME (synchronized across the robot's computers by chrony or
/// PTP), so each stamp is converted once, at the publisher:
///
///   stamp = t_monotonic + offset,   offset = CLOCK_REALTIME − CLOCK_MONOTONIC
///
/// The offset is sampled (Update, once per publisher wake, ≤ 20 ms apart) as a tight pair of
/// clock reads: monotonic, realtime, monotonic, retried while preemption splits the pair by
/// more than kMaxPairGapNs, the realtime read set against the two monotonic reads' midpoint.
/// Every later stamp uses the newest offset, so a step of the wall clock moves the stamps at
/// the next publisher wake while the estimator's time never jumps.
///
/// Step or slew: NTP and PTP slew the wall clock through adjtimex(2), whose frequency term is
/// bounded to ±500 ppm and whose tick term to ±10 % (chrony's default maxslewrate, 83,333 ppm,
/// uses the tick). A slew therefore changes the offset by at most 10 % of the monotonic time
/// between two samples. A change larger than kStepMinNs + 10 % · Δt is a step (settimeofday,
/// chronyd's makestep, phc2sys's first step): it is counted and returned for one log line.
/// kStepMinNs (1 ms) is far above the pair's noise (≤ kMaxPairGapNs / 2) and far below any
/// step worth reporting; a smaller jump is followed all the same, only not counted.
///
/// Mode "monotonic" (ipc.stamp_clock) keeps the stamps on CLOCK_MONOTONIC (ToStamp is the
/// identity); the offset is still tracked, so health and recordings can relate the two.
///
/// Thread roles: Update on one thread (the publisher); ToStamp, offset_ns and counters from any
/// thread (relaxed atomics; the map publisher stamps on the loop-closure thread).

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

namespace swlio::daemon {

/// A clock read in ns; injectable so that tests can step the wall clock (time namespaces do
/// not virtualize CLOCK_REALTIME).
using ClockNowFn = std::function<int64_t()>;

/// CLOCK_REALTIME in ns.
int64_t RealtimeNowNs();

/// The two clocks the offset is read from (defaults: the host's).
struct ClockSources {
  ClockNowFn monotonic;  ///< empty: CLOCK_MONOTONIC
  ClockNowFn realtime;   ///< empty: CLOCK_REALTIME
};

/// One reading of realtime − monotonic.
struct ClockOffsetSample {
  int64_t t_monotonic_ns = 0;  ///< midpoint of the pair's monotonic reads
  int64_t offset_ns = 0;       ///< realtime − monotonic
};

/// Reads the pair (the tightest of up to kPairAttempts).
ClockOffsetSample SampleClockOffset(const ClockSources& clocks);

/// A step of the wall clock, as Update found it.
struct WallClockStep {
  int64_t t_monotonic_ns = 0;  ///< when it was seen
  int64_t step_ns = 0;         ///< change of the offset (+: the wall clock jumped ahead)
  int64_t offset_ns = 0;       ///< the offset after it
};

struct StampClockCounters {
  bool realtime = true;                ///< stamps on CLOCK_REALTIME (else CLOCK_MONOTONIC)
  int64_t offset_ns = 0;               ///< newest realtime − monotonic
  uint64_t steps = 0;                  ///< wall-clock steps seen since the start
  int64_t last_step_ns = 0;            ///< size of the newest step (0: none)
  int64_t last_step_monotonic_ns = 0;  ///< when it was seen
};

class StampClock {
 public:
  static constexpr int64_t kStepMinNs = 1'000'000;  ///< 1 ms
  static constexpr double kMaxSlewFraction = 0.1;   ///< adjtimex tick: ±10 %
  static constexpr int64_t kMaxPairGapNs = 50'000;  ///< a preempted pair is read again
  static constexpr int kPairAttempts = 3;

  /// `realtime`: stamps on CLOCK_REALTIME (ipc.stamp_clock realtime). Samples the offset once.
  explicit StampClock(bool realtime, ClockSources clocks = {});

  /// Samples the offset; the step when it jumped by more than a slew can explain.
  std::optional<WallClockStep> Update();
  /// A host time (CLOCK_MONOTONIC; a --time-scale'd daemon time goes back to host time first)
  /// as the message stamp.
  int64_t ToStamp(int64_t t_monotonic_ns) const {
    return realtime_ ? t_monotonic_ns + offset_ns_.load(std::memory_order_relaxed) : t_monotonic_ns;
  }
  int64_t offset_ns() const { return offset_ns_.load(std::memory_order_relaxed); }
  bool realtime() const { return realtime_; }
  const ClockSources& clocks() const { return clocks_; }
  StampClockCounters counters() const;

 private:
  bool realtime_;
  ClockSources clocks_;
  int64_t last_t_ns_ = 0;  ///< Update's thread only
  std::atomic<int64_t> offset_ns_{0};
  std::atomic<uint64_t> steps_{0};
  std::atomic<int64_t> last_step_ns_{0};
  std::atomic<int64_t> last_step_t_ns_{0};
};

/// "realtime" → true, "monotonic" → false (IpcConfig::stamp_clock, validated).
inline bool IsRealtimeStampClock(const std::string_view name) { return name == "realtime"; }

}  // namespace swlio::daemon

#pragma once
/// @file
/// Kernel receive timestamps → host time (CLOCK_MONOTONIC ns), shared by the UDP and CAN
/// shells.
///
/// SO_TIMESTAMPNS (socket(7)) stamps each packet in software when the kernel receives it, on
/// CLOCK_REALTIME. swlio's host clock is CLOCK_MONOTONIC, so each stamp is shifted by the
/// offset (monotonic − realtime) measured when the batch is read: one realtime reading taken
/// between two monotonic readings, offset = mid(monotonic) − realtime. Its error is at most half
/// the time between the two monotonic readings. A thread preempted between them (a busy
/// machine, or tests run in parallel) made that gap hundreds of µs, which put one batch's stamps
/// before the previous batch's. So up to kClockReadTries readings are taken and the tightest is
/// kept, stopping at one within kTightClockReadNs (TightestClockReading). The conversion is
/// then exact unless the realtime clock was stepped (settimeofday, an NTP step) between the
/// kernel's stamp and our read, typically microseconds to milliseconds; slewing (adjtime)
/// changes the two clocks' rates alike and does not matter. A converted stamp later than the read
/// time, or more than `kMaxStampAgeNs` before it, proves such a step: it is replaced by the read
/// time and counted. (SO_TIMESTAMPING's software stamps are also CLOCK_REALTIME, so it would not
/// avoid this conversion; hardware stamps are on the NIC clock and need PTP, which we do not
/// assume.)

#include <sys/socket.h>
#include <time.h>

#include <cstdint>
#include <optional>

namespace swlio::drivers {

/// Older than this (before the read) a converted kernel stamp is taken as wrong.
inline constexpr int64_t kMaxStampAgeNs = 5'000'000'000;

/// CLOCK_MONOTONIC now, ns.
int64_t MonotonicNowNs();

/// Readings of the offset taken at most, and the time between a reading's two monotonic reads
/// (a few vDSO calls, well under 1 µs when not preempted) that ends the search early.
inline constexpr int kClockReadTries = 4;
inline constexpr int64_t kTightClockReadNs = 5'000;

/// One reading: CLOCK_MONOTONIC, CLOCK_REALTIME, CLOCK_MONOTONIC, in that order (ns).
struct ClockReading {
  int64_t mono_before_ns = 0;
  int64_t real_ns = 0;
  int64_t mono_after_ns = 0;

  int64_t gap_ns() const { return mono_after_ns - mono_before_ns; }
  /// Midpoint of the two monotonic reads: the monotonic time the realtime read is set against.
  int64_t mono_mid_ns() const { return mono_before_ns + gap_ns() / 2; }
};

/// Up to `tries` readings from `read` (a callable returning a ClockReading), the tightest kept
/// (the first of equals); stops at one whose gap is within `tight_ns`. Shared by the kernel
/// stamps' conversion here and the daemon's published stamps (stamp_clock.h).
template <class ReadFn>
ClockReading TightestClockReading(ReadFn&& read, int tries, int64_t tight_ns) {
  ClockReading best = read();
  for (int i = 1; i < tries && best.gap_ns() > tight_ns; ++i) {
    const ClockReading r = read();
    if (r.gap_ns() < best.gap_ns()) best = r;
  }
  return best;
}

/// A reading of the system clocks.
ClockReading ReadSystemClocks();

/// The monotonic − realtime offset at this moment, with the monotonic read time.
struct RealtimeToMonotonic {
  int64_t offset_ns = 0;  ///< add to a CLOCK_REALTIME time to get CLOCK_MONOTONIC
  int64_t read_mono_ns = 0;

  /// From the system clocks: the tightest of up to kClockReadTries readings.
  static RealtimeToMonotonic Measure();
  /// From one reading.
  static RealtimeToMonotonic FromReading(const ClockReading& reading);

  /// Host time of a kernel stamp; std::nullopt when it is implausible (see file comment).
  std::optional<int64_t> Convert(const timespec& realtime_stamp) const;
};

/// Turns SO_TIMESTAMPNS on; false when the socket refuses it.
bool EnableRxTimestampNs(int fd);

/// The SCM_TIMESTAMPNS stamp in a received message's control data, if present.
std::optional<timespec> FindRxTimestampNs(const msghdr& msg);

/// Control-buffer size that holds one SCM_TIMESTAMPNS message.
inline constexpr size_t kRxTimestampControlBytes = CMSG_SPACE(sizeof(timespec));

}  // namespace swlio::drivers

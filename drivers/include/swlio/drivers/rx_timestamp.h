#pragma once
/// @file
/// Kernel receive timestamps → host time (CLOCK_MONOTONIC ns), shared by the UDP and CAN
/// shells.
///
/// SO_TIMESTAMPNS (socket(7)) stamps each packet in software when the kernel receives it, on
/// CLOCK_REALTIME. swlio's host clock is CLOCK_MONOTONIC, so each stamp is shifted by the
/// offset (monotonic − realtime) measured when the batch is read: one realtime reading taken
/// between two monotonic readings, offset = mid(monotonic) − realtime. The conversion is exact
/// unless the realtime clock was stepped (settimeofday, an NTP step) between the kernel's stamp
/// and our read, typically microseconds to milliseconds; slewing (adjtime) changes the two
/// clocks' rates alike and does not matter. A converted stamp later than the read time, or more
/// than `kMaxStampAgeNs` before it, proves such a step: it is replaced by the read time and
/// counted. (SO_TIMESTAMPING's software stamps are also CLOCK_REALTIME, so it would not avoid
/// this conversion; hardware stamps are on the NIC clock and need PTP, which we do not assume.)

#include <sys/socket.h>
#include <time.h>

#include <cstdint>
#include <optional>

namespace swlio::drivers {

/// Older than this (before the read) a converted kernel stamp is taken as wrong.
inline constexpr int64_t kMaxStampAgeNs = 5'000'000'000;

/// CLOCK_MONOTONIC now, ns.
int64_t MonotonicNowNs();

/// The monotonic − realtime offset at this moment, with the monotonic read time.
struct RealtimeToMonotonic {
  int64_t offset_ns = 0;  ///< add to a CLOCK_REALTIME time to get CLOCK_MONOTONIC
  int64_t read_mono_ns = 0;

  static RealtimeToMonotonic Measure();

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

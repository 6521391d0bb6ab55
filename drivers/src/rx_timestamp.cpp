// Kernel receive timestamps (socket(7): SO_TIMESTAMPNS, control message SCM_TIMESTAMPNS with a
// struct timespec on CLOCK_REALTIME) and their conversion to CLOCK_MONOTONIC; see the header.

#include "swlio/drivers/rx_timestamp.h"

#include <cstring>

#include "swlio/core/time.h"

namespace swlio::drivers {
namespace {

int64_t ToNs(const timespec& ts) {
  return static_cast<int64_t>(ts.tv_sec) * kNsPerSec + static_cast<int64_t>(ts.tv_nsec);
}

int64_t ClockNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return ToNs(ts);
}

}  // namespace

int64_t MonotonicNowNs() { return ClockNs(CLOCK_MONOTONIC); }

ClockReading ReadSystemClocks() {
  ClockReading r;
  r.mono_before_ns = ClockNs(CLOCK_MONOTONIC);
  r.real_ns = ClockNs(CLOCK_REALTIME);
  r.mono_after_ns = ClockNs(CLOCK_MONOTONIC);
  return r;
}

RealtimeToMonotonic RealtimeToMonotonic::Measure() {
  return FromReading(TightestClockReading(ReadSystemClocks, kClockReadTries, kTightClockReadNs));
}

RealtimeToMonotonic RealtimeToMonotonic::FromReading(const ClockReading& reading) {
  return {reading.mono_mid_ns() - reading.real_ns, reading.mono_after_ns};
}

std::optional<int64_t> RealtimeToMonotonic::Convert(const timespec& realtime_stamp) const {
  if (realtime_stamp.tv_sec == 0 && realtime_stamp.tv_nsec == 0) return std::nullopt;
  const int64_t t = ToNs(realtime_stamp) + offset_ns;
  // A small tolerance above the read time absorbs the half-interval of Measure().
  if (t > read_mono_ns + kNsPerMs || t < read_mono_ns - kMaxStampAgeNs) return std::nullopt;
  return t;
}

bool EnableRxTimestampNs(int fd) {
  const int on = 1;
  return setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof(on)) == 0;
}

std::optional<timespec> FindRxTimestampNs(const msghdr& msg) {
  if (msg.msg_control == nullptr || (msg.msg_flags & MSG_CTRUNC) != 0) return std::nullopt;
  for (const cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr;
       c = CMSG_NXTHDR(const_cast<msghdr*>(&msg), const_cast<cmsghdr*>(c))) {
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS &&
        c->cmsg_len >= CMSG_LEN(sizeof(timespec))) {
      timespec ts{};
      std::memcpy(&ts, CMSG_DATA(c), sizeof(ts));  // CMSG_DATA may be unaligned for timespec
      return ts;
    }
  }
  return std::nullopt;
}

}  // namespace swlio::drivers

#pragma once
/// @file
/// Time in swlio: one representation, `int64_t` nanoseconds.
///
/// Host times are nanoseconds of CLOCK_MONOTONIC (stamped by the I/O shells, kernel receive
/// timestamps preferred). Sensor clocks travel alongside as their own `int64_t` ns and are mapped
/// to host time in exactly one place (the clock model). `double` seconds appear only as `dt`
/// inside the maths, converted at the last moment with the helpers below.

#include <cstdint>

namespace swlio {

inline constexpr int64_t kNsPerUs = 1'000;
inline constexpr int64_t kNsPerMs = 1'000'000;
inline constexpr int64_t kNsPerSec = 1'000'000'000;

/// Nanoseconds → seconds, for `dt` in formulas only.
constexpr double NsToSec(int64_t ns) { return static_cast<double>(ns) * 1e-9; }

/// Seconds → nanoseconds, rounded to the nearest nanosecond.
constexpr int64_t SecToNs(double sec) {
  const double ns = sec * 1e9;
  return static_cast<int64_t>(ns < 0.0 ? ns - 0.5 : ns + 0.5);
}

}  // namespace swlio

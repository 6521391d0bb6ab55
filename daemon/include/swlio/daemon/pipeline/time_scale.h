#pragma once
/// @file
/// The daemon's time base against the host clock, for sensors whose clocks run `scale` times
/// faster than the host: the simulator streaming at `--speed N` (its sensor clocks follow the
/// simulated time). Physics needs the sensors' time: with N = 2 a host-time IMU interval would
/// be half the one the accelerometer integrated over. So host receive times are stretched
/// about `origin_ns` before the clock models (daemon time τ = origin + (host − origin)·N), the
/// estimator runs on τ, and published stamps go back to host time. N = 1 (every real robot)
/// is the identity.

#include <cmath>
#include <cstdint>

namespace swlio::daemon {

struct TimeScale {
  int64_t origin_ns = 0;  ///< host time where both time bases agree
  double scale = 1.0;     ///< sensor seconds per host second

  int64_t ToDaemon(int64_t host_ns) const {
    if (scale == 1.0) return host_ns;
    return origin_ns + std::llround(static_cast<double>(host_ns - origin_ns) * scale);
  }
  int64_t ToHost(int64_t daemon_ns) const {
    if (scale == 1.0) return daemon_ns;
    return origin_ns + std::llround(static_cast<double>(daemon_ns - origin_ns) / scale);
  }
};

}  // namespace swlio::daemon

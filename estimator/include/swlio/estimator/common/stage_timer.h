#pragma once
/// @file
/// Per-stage timing without a clock in the library: the caller injects a monotonic time source
/// (the daemon and the tools pass `CLOCK_MONOTONIC`; tests may pass a fake or none, and then
/// every stage reads 0).

#include <cstdint>

namespace swlio::estimator {

/// Returns the current time in ns from any monotonic clock; nullptr disables timing.
using NowNsFn = int64_t (*)();

/// Time spent per scan in each stage, ms. A stage that did not run is 0.
struct StageTimes {
  double frontend_ms = 0.0;  ///< de-skew, segmentation, features, voxel filter
  double match_ms = 0.0;     ///< scan-to-map registration (correspondences and solve)
  double optimize_ms = 0.0;  ///< window optimization (tightly coupled mode only)
  /// A keyframe's local-map upkeep: moving objects out (visibility_image.h) and its features
  /// in (tightly coupled mode only; 0 on other sweeps).
  double map_ms = 0.0;
  double total_ms = 0.0;  ///< the whole scan update
};

/// Stopwatch over an injected clock.
class StageTimer {
 public:
  explicit StageTimer(NowNsFn now_ns) : now_ns_(now_ns), start_ns_(Now()) {}
  /// Milliseconds since construction or the previous Lap.
  double Lap() {
    const int64_t t = Now();
    const double ms = static_cast<double>(t - start_ns_) * 1e-6;
    start_ns_ = t;
    return ms;
  }

 private:
  int64_t Now() const { return now_ns_ != nullptr ? now_ns_() : 0; }
  NowNsFn now_ns_;
  int64_t start_ns_;
};

}  // namespace swlio::estimator

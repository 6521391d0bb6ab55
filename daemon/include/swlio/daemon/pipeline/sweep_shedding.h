#pragma once
/// @file
/// Which sweeps the optimizer thread skips when the estimator runs behind its input.
///
/// A loaded computer (or a simulator streaming faster than the estimator can follow) makes the
/// LiDAR packets queue up. Left alone, the backlog grows until the packet queue overflows in
/// the middle of sweeps: packets are lost, sweeps arrive partial, the estimate is seconds old,
/// and the IMU has to bridge gaps the estimator never chose (a 2-hour soak at 10× on two cores
/// diverged that way). Instead, a sweep whose last packet arrived more than `max_lag_ns` ago
/// (daemon time) is skipped, never two in a row: while behind, every other sweep is processed,
/// which halves the estimator's load until it has caught up. The IMU carries the state across
/// a skipped sweep (one pre-integration over 0.2 s instead of two over 0.1 s), and the
/// IMU-rate pose output is not affected. Each skip is counted (health
/// `sweeps_skipped_behind`).

#include <cstdint>

namespace swlio::daemon {

class SweepShedding {
 public:
  /// `max_lag_ns` ≤ 0: never skip.
  explicit SweepShedding(int64_t max_lag_ns = 0) : max_lag_ns_(max_lag_ns) {}

  /// Whether to process a sweep whose last packet arrived `lag_ns` ago; false: skip it.
  bool Take(int64_t lag_ns) {
    const bool skip = max_lag_ns_ > 0 && lag_ns > max_lag_ns_ && !skipped_last_;
    skipped_last_ = skip;
    if (skip) ++skipped_;
    return !skip;
  }

  uint64_t skipped() const { return skipped_; }

 private:
  int64_t max_lag_ns_;
  bool skipped_last_ = false;
  uint64_t skipped_ = 0;
};

}  // namespace swlio::daemon

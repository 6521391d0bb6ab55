#pragma once
/// @file
/// Which sweeps the optimizer thread skips when the estimator runs behind its input.
///
/// A loaded computer (or a simulator streaming faster than the estimator can follow) makes the
/// LiDAR packets queue up. Left alone, the backlog grows until the packet queue overflows in
/// the middle of sweeps: packets are lost, sweeps arrive partial, the estimate is seconds old,
/// and the IMU has to bridge gaps the estimator never chose (a 2-hour soak at 10× on two cores
/// diverged that way). Instead, a sweep whose last packet arrived more than `max_lag_ns` ago
/// (daemon time) is skipped. While behind by up to 2 × `max_lag_ns`, every other sweep is
/// processed, which halves the estimator's load until it has caught up; further behind (the
/// CPU truly does not suffice: a quota, a core shared with heavier work), up to one more sweep
/// in a row is skipped per `max_lag_ns` of lag, at most `kMaxRun` (the IMU then bridges 0.5 s at
/// 10 Hz), which cuts the load to a fifth. The IMU carries the state across skipped sweeps
/// (one pre-integration over their span), and the IMU-rate pose output is not affected. Each
/// skip is counted (health `sweeps_skipped_behind`).

#include <algorithm>
#include <cstdint>

namespace swlio::daemon {

class SweepShedding {
 public:
  /// The most sweeps skipped in a row, however far behind.
  static constexpr int kMaxRun = 4;

  /// `max_lag_ns` ≤ 0: never skip.
  explicit SweepShedding(int64_t max_lag_ns = 0) : max_lag_ns_(max_lag_ns) {}

  /// Whether to process a sweep whose last packet arrived `lag_ns` ago; false: skip it.
  bool Take(int64_t lag_ns) {
    const bool skip = max_lag_ns_ > 0 && lag_ns > max_lag_ns_ && run_ < AllowedRun(lag_ns);
    run_ = skip ? run_ + 1 : 0;
    if (skip) ++skipped_;
    return !skip;
  }

  uint64_t skipped() const { return skipped_; }

 private:
  /// Sweeps that may be skipped in a row at this lag: 1 up to 2 × max_lag_ns, then one more
  /// per max_lag_ns, up to kMaxRun.
  int AllowedRun(int64_t lag_ns) const {
    const int64_t run = std::max<int64_t>(1, (lag_ns - 1) / max_lag_ns_);
    return static_cast<int>(std::min<int64_t>(run, kMaxRun));
  }

  int64_t max_lag_ns_;
  int run_ = 0;  ///< sweeps skipped in a row just before
  uint64_t skipped_ = 0;
};

}  // namespace swlio::daemon

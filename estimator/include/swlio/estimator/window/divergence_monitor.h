#pragma once
/// @file
/// Divergence detection for the tightly coupled window (issue 9): after every sweep, is the
/// newest state still believable? When not, the window re-initializes (window_estimator.h)
/// instead of dead-reckoning on a broken state, and the reason is reported.
///
/// A state is taken for diverged when, for the newest frame:
///  - its speed exceeds `max_speed_mps` (a ground robot: LIO-SAM's "large velocity" case);
///  - an accelerometer or gyro bias exceeds its bound (the MTi-G-710's are a few mg and
///    0.2 °/s after turn-on, datasheet; the defaults are 30–50× that);
///  - the LiDAR matched too few features for `max_failed_sweeps` sweeps in a row (the IMU alone
///    carried the state that long; its error grows with the cube of time);
///  - the IMU prediction and the newest sweep's own registration against the map disagree by
///    more than `max_prediction_error_m` or `max_prediction_error_rad` for
///    `max_inconsistent_sweeps` sweeps in a row (one sweep may be a bad registration; several
///    mean the IMU integration or the state is wrong).
/// Pure: no clock, no logging.

#include <cstddef>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"

namespace swlio::estimator {

struct DivergenceConfig {
  bool enabled = true;  ///< false: report nothing, never re-initialize
  double max_speed_mps = 5.0;
  double max_bias_acc_mps2 = 1.0;
  double max_bias_gyro_radps = 0.1;
  int max_failed_sweeps = 20;  ///< 2 s at 10 Hz
  double max_prediction_error_m = 1.0;
  double max_prediction_error_rad = 0.17;  ///< ≈ 10°
  int max_inconsistent_sweeps = 3;
  ConfigIssues Validate() const;
};

enum class DivergenceReason {
  kNone,
  kSpeed,         ///< |v| > max_speed_mps
  kBiasAcc,       ///< |b_a| > max_bias_acc_mps2
  kBiasGyro,      ///< |b_g| > max_bias_gyro_radps
  kLidarLost,     ///< max_failed_sweeps sweeps in a row without enough matches
  kInconsistent,  ///< IMU prediction and LiDAR registration disagree, repeatedly
};

const char* ToString(DivergenceReason reason);

/// What one sweep tells the monitor.
struct SweepCheck {
  State state;                ///< the newest frame after the solve
  bool match_failed = false;  ///< too few LiDAR matches
  /// The sweep's registration moved the IMU prediction by this much (negative: no
  /// registration this sweep, e.g. no map yet or the registration did not converge).
  double prediction_error_m = -1.0;
  double prediction_error_rad = -1.0;
};

class DivergenceMonitor {
 public:
  explicit DivergenceMonitor(const DivergenceConfig& config) : config_(config) {}

  /// kNone while the state is believable; else why not (the counters then start over).
  DivergenceReason Check(const SweepCheck& sweep);
  /// Forgets the counts of failed and inconsistent sweeps (after a re-initialization).
  void Reset();

 private:
  DivergenceConfig config_;
  int failed_in_a_row_ = 0;
  int inconsistent_in_a_row_ = 0;
};

}  // namespace swlio::estimator

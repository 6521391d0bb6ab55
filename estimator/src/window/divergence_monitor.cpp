#include "swlio/estimator/window/divergence_monitor.h"

namespace swlio::estimator {

ConfigIssues DivergenceConfig::Validate() const {
  ConfigIssues issues;
  CheckPositive(issues, "max_speed_mps", max_speed_mps);
  CheckPositive(issues, "max_bias_acc_mps2", max_bias_acc_mps2);
  CheckPositive(issues, "max_bias_gyro_radps", max_bias_gyro_radps);
  CheckInRange(issues, "max_failed_sweeps", max_failed_sweeps, 1, 100000);
  CheckPositive(issues, "max_prediction_error_m", max_prediction_error_m);
  CheckInRange(issues, "max_prediction_error_rad", max_prediction_error_rad, 1e-3, 3.14159);
  CheckInRange(issues, "max_inconsistent_sweeps", max_inconsistent_sweeps, 1, 100000);
  return issues;
}

const char* ToString(DivergenceReason reason) {
  switch (reason) {
    case DivergenceReason::kNone:
      return "none";
    case DivergenceReason::kSpeed:
      return "speed out of bounds";
    case DivergenceReason::kBiasAcc:
      return "accelerometer bias out of bounds";
    case DivergenceReason::kBiasGyro:
      return "gyro bias out of bounds";
    case DivergenceReason::kLidarLost:
      return "LiDAR matches lost";
    case DivergenceReason::kInconsistent:
      return "IMU and LiDAR disagree";
  }
  return "unknown";
}

DivergenceReason DivergenceMonitor::Check(const SweepCheck& sweep) {
  if (!config_.enabled) return DivergenceReason::kNone;
  const State& s = sweep.state;
  DivergenceReason reason = DivergenceReason::kNone;
  // NaN compares false everywhere: a non-finite state counts as out of bounds.
  if (!(s.vel_world.norm() <= config_.max_speed_mps)) reason = DivergenceReason::kSpeed;
  if (!(s.bias_acc.norm() <= config_.max_bias_acc_mps2)) reason = DivergenceReason::kBiasAcc;
  if (!(s.bias_gyro.norm() <= config_.max_bias_gyro_radps)) reason = DivergenceReason::kBiasGyro;

  failed_in_a_row_ = sweep.match_failed ? failed_in_a_row_ + 1 : 0;
  if (reason == DivergenceReason::kNone && failed_in_a_row_ >= config_.max_failed_sweeps)
    reason = DivergenceReason::kLidarLost;

  const bool registered = sweep.prediction_error_m >= 0.0;
  const bool disagree =
      registered && (sweep.prediction_error_m > config_.max_prediction_error_m ||
                     sweep.prediction_error_rad > config_.max_prediction_error_rad);
  if (registered) inconsistent_in_a_row_ = disagree ? inconsistent_in_a_row_ + 1 : 0;
  if (reason == DivergenceReason::kNone &&
      inconsistent_in_a_row_ >= config_.max_inconsistent_sweeps)
    reason = DivergenceReason::kInconsistent;

  if (reason != DivergenceReason::kNone) Reset();
  return reason;
}

void DivergenceMonitor::Reset() {
  failed_in_a_row_ = 0;
  inconsistent_in_a_row_ = 0;
}

}  // namespace swlio::estimator

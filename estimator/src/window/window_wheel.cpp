// WindowEstimator's wheel odometry: the samples around a frame's time become its velocity
// factor (wheel_velocity_factor.h).

#include <cmath>
#include <cstdlib>

#include "swlio/core/time.h"
#include "swlio/estimator/window/window_estimator.h"
#include "window_frame.h"

namespace swlio::estimator {

void WindowEstimator::AddWheel(const WheelOdometry& sample) {
  if (!config_.wheel.enabled) return;
  if (!std::isfinite(sample.linear_velocity_mps)) return;
  if (!wheel_.empty() && sample.t_ns < wheel_.back().t_ns) return;  // out of order: not used
  wheel_.push_back(sample);
  while (wheel_.front().t_ns < sample.t_ns - kNsPerSec) wheel_.pop_front();
}

Eigen::Vector3d WindowEstimator::GyroAt(int64_t t_ns) const {
  const ImuSample* best = nullptr;
  for (const ImuSample& s : imu_) {
    if (best == nullptr || std::llabs(s.t_ns - t_ns) < std::llabs(best->t_ns - t_ns)) best = &s;
  }
  return best != nullptr ? best->gyro_radps : Eigen::Vector3d::Zero();
}

namespace {

/// Forward speed at `t_ns`: interpolated between the samples around it, or the nearest one
/// held; false when none is within `max_gap_ns`.
bool WheelSpeedAt(const std::deque<WheelOdometry>& samples,
                  int64_t t_ns,
                  int64_t max_gap_ns,
                  double* speed_mps) {
  const WheelOdometry* before = nullptr;
  const WheelOdometry* after = nullptr;
  for (const WheelOdometry& s : samples) {
    if (s.t_ns <= t_ns) before = &s;
    if (s.t_ns >= t_ns) {
      after = &s;
      break;
    }
  }
  const bool near_before = before != nullptr && t_ns - before->t_ns <= max_gap_ns;
  const bool near_after = after != nullptr && after->t_ns - t_ns <= max_gap_ns;
  if (near_before && near_after && after->t_ns > before->t_ns) {
    const double a =
        static_cast<double>(t_ns - before->t_ns) / static_cast<double>(after->t_ns - before->t_ns);
    *speed_mps = (1.0 - a) * before->linear_velocity_mps + a * after->linear_velocity_mps;
    return true;
  }
  if (near_before || near_after) {
    *speed_mps = near_before ? before->linear_velocity_mps : after->linear_velocity_mps;
    return true;
  }
  return false;
}

}  // namespace

bool WindowEstimator::AttachWheel(Frame* frame) {
  double speed_mps = 0.0;
  const auto max_gap_ns = static_cast<int64_t>(config_.wheel.max_gap_s * 1e9);
  if (!WheelSpeedAt(wheel_, frame->t_ns, max_gap_ns, &speed_mps)) return false;
  const WheelFactorConfig& c = config_.wheel;
  auto factor =
      WheelVelocityFactor::Create(speed_mps, GyroAt(frame->t_ns), c.T_imu_base.ToIsometry(),
                                  {.forward_mps = c.sigma_forward_mps,
                                   .lateral_mps = c.sigma_lateral_mps,
                                   .vertical_mps = c.sigma_vertical_mps});
  if (factor == nullptr) return false;
  // Slip gate against the IMU prediction (the frame's state before the solve).
  const double predicted_mps =
      factor->BaseVelocity(frame->pose.data(), frame->speed_bias.data()).x();
  if (std::abs(predicted_mps - speed_mps) > c.max_innovation_mps) {
    ++wheel_rejected_;
    return false;
  }
  frame->wheel = std::move(factor);
  ++wheel_factors_;
  return true;
}

}  // namespace swlio::estimator

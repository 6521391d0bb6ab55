#include "swlio/estimator/imu/imu_rate_propagator.h"

#include <algorithm>

#include "swlio/estimator/imu/imu_propagator.h"

namespace swlio::estimator {

ConfigIssues ImuRatePropagatorConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "gravity_mps2", gravity_mps2, 9.7, 9.9);
  CheckInRange(issues, "buffer_samples", buffer_samples, size_t{2}, size_t{1'000'000});
  CheckInRange(issues, "rebase_rate_mps", rebase_rate_mps, 0.0, 10.0);
  CheckInRange(issues, "rebase_rate_radps", rebase_rate_radps, 0.0, 10.0);
  CheckInRange(issues, "rebase_max_m", rebase_max_m, 0.0, 10.0);
  CheckInRange(issues, "rebase_max_rad", rebase_max_rad, 0.0, 3.2);
  CheckThat(issues, (rebase_rate_mps > 0.0) == (rebase_rate_radps > 0.0), "rebase_rate_radps",
            "must be 0 exactly when rebase_rate_mps is");
  return issues;
}

ImuRatePropagator::ImuRatePropagator(const ImuRatePropagatorConfig& config)
    : gravity_mps2_(config.gravity_mps2),
      config_(config),
      ring_(std::max<size_t>(config.buffer_samples, 2)) {}

void ImuRatePropagator::Push(const ImuSample& sample) {
  if (size_ == ring_.size()) {
    head_ = (head_ + 1) % ring_.size();
    --size_;
    ++counters_.overflow_dropped;
  }
  ring_[(head_ + size_) % ring_.size()] = sample;
  ++size_;
  ++counters_.samples;
}

void ImuRatePropagator::DropUpTo(int64_t t_ns) {
  // Keep the last sample at or before t_ns: the left end of the interval straddling t_ns.
  while (size_ >= 2 && At(1).t_ns <= t_ns) {
    head_ = (head_ + 1) % ring_.size();
    --size_;
  }
}

namespace {

/// Moves `T` toward the identity by at most `m` and `rad`.
void Shrink(Eigen::Isometry3d* T, double m, double rad) {
  const Eigen::Vector3d t = T->translation();
  const double n = t.norm();
  T->translation() = n <= m ? Eigen::Vector3d::Zero() : Eigen::Vector3d(t * ((n - m) / n));
  Eigen::AngleAxisd aa(T->linear());
  aa.angle() = std::max(0.0, aa.angle() - rad);
  T->linear() = aa.toRotationMatrix();
}

}  // namespace

ImuRateOutput ImuRatePropagator::Output(const ImuSample* newest) {
  ImuRateOutput out;
  out.state = current_;
  if (config_.rebase_rate_mps > 0.0 || config_.rebase_rate_radps > 0.0) {
    const double dt_s =
        has_output_
            ? static_cast<double>(std::max<int64_t>(current_.t_ns - last_output_t_ns_, 0)) * 1e-9
            : 0.0;
    Shrink(&rebase_, config_.rebase_rate_mps * dt_s, config_.rebase_rate_radps * dt_s);
    // In the body frame: taking a rotation in turns the body about itself, never swings it
    // about the world origin (hundreds of metres away on a long drive).
    out.state.T_world_imu = current_.T_world_imu * rebase_;
  }
  has_output_ = true;
  last_output_ = out.state.T_world_imu;
  last_output_t_ns_ = current_.t_ns;
  if (newest != nullptr) out.gyro_imu_radps = newest->gyro_radps - current_.bias_gyro;
  out.since_optimized_ns = current_.t_ns - optimized_t_ns_;
  return out;
}

void ImuRatePropagator::Clear() {
  head_ = 0;
  size_ = 0;
  has_state_ = false;
  optimized_t_ns_ = 0;
  rebase_ = Eigen::Isometry3d::Identity();
  has_output_ = false;
}

std::optional<ImuRateOutput> ImuRatePropagator::SetState(const State& optimized) {
  if (has_state_ && optimized.t_ns < optimized_t_ns_) {
    ++counters_.stale_states;
    return std::nullopt;
  }
  has_state_ = true;
  optimized_t_ns_ = optimized.t_ns;
  current_ = optimized;
  ++counters_.states;
  DropUpTo(optimized.t_ns);
  for (size_t i = 0; i < size_; ++i) {
    if (StrapdownStep(gravity_mps2_, At(i), &current_)) ++counters_.repropagated;
  }
  // Keep the last output where it was (same instant: the newest sample) and take the
  // correction in over the next samples; a large one at once.
  if (has_output_ && (config_.rebase_rate_mps > 0.0 || config_.rebase_rate_radps > 0.0)) {
    const Eigen::Isometry3d offset = current_.T_world_imu.inverse() * last_output_;
    const bool small = offset.translation().norm() <= config_.rebase_max_m &&
                       Eigen::AngleAxisd(offset.linear()).angle() <= config_.rebase_max_rad;
    rebase_ = small ? offset : Eigen::Isometry3d::Identity();
  }
  return Output(size_ > 0 ? &At(size_ - 1) : nullptr);
}

std::optional<ImuRateOutput> ImuRatePropagator::Add(const ImuSample& sample) {
  if (size_ > 0 && sample.t_ns <= At(size_ - 1).t_ns) {
    ++counters_.out_of_order;
    return std::nullopt;
  }
  Push(sample);
  if (!has_state_ || !StrapdownStep(gravity_mps2_, sample, &current_)) {
    ++counters_.before_state;
    return std::nullopt;
  }
  return Output(&sample);
}

}  // namespace swlio::estimator

#include "swlio/estimator/imu/imu_rate_propagator.h"

#include <algorithm>

#include "swlio/estimator/imu/imu_propagator.h"

namespace swlio::estimator {

ConfigIssues ImuRatePropagatorConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "gravity_mps2", gravity_mps2, 9.7, 9.9);
  CheckInRange(issues, "buffer_samples", buffer_samples, size_t{2}, size_t{1'000'000});
  return issues;
}

ImuRatePropagator::ImuRatePropagator(const ImuRatePropagatorConfig& config)
    : gravity_mps2_(config.gravity_mps2), ring_(std::max<size_t>(config.buffer_samples, 2)) {}

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

ImuRateOutput ImuRatePropagator::Output(const ImuSample* newest) const {
  ImuRateOutput out;
  out.state = current_;
  if (newest != nullptr) out.gyro_imu_radps = newest->gyro_radps - current_.bias_gyro;
  out.since_optimized_ns = current_.t_ns - optimized_t_ns_;
  return out;
}

void ImuRatePropagator::Clear() {
  head_ = 0;
  size_ = 0;
  has_state_ = false;
  optimized_t_ns_ = 0;
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
  const ImuSample* previous = nullptr;
  for (size_t i = 0; i < size_; ++i) {
    const ImuSample& sample = At(i);
    if (StrapdownStep(gravity_mps2_, previous, sample, &current_)) ++counters_.repropagated;
    previous = &sample;
  }
  return Output(previous);
}

std::optional<ImuRateOutput> ImuRatePropagator::Add(const ImuSample& sample) {
  if (size_ > 0 && sample.t_ns <= At(size_ - 1).t_ns) {
    ++counters_.out_of_order;
    return std::nullopt;
  }
  Push(sample);
  const ImuSample* previous = size_ >= 2 ? &At(size_ - 2) : nullptr;
  if (!has_state_ || !StrapdownStep(gravity_mps2_, previous, sample, &current_)) {
    ++counters_.before_state;
    return std::nullopt;
  }
  return Output(&sample);
}

}  // namespace swlio::estimator

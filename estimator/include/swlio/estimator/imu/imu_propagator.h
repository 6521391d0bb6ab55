#pragma once
/// @file
/// Strapdown propagation of a navigation state with bias-corrected IMU samples, recording the
/// pose at every sample (the track de-skew interpolates in).
///
/// Between samples k−1 and k (dt), with ω̄, f̄ sample k's bias-corrected values (the means over
/// its interval, core/types.h) and g = (0, 0, −g) in the world frame:
///   R_k = R_{k−1}·Exp(ω̄·dt)
///   a   = R_{k−1}·Exp(½ω̄·dt)·f̄ + g          (attitude at the interval's middle)
///   p_k = p_{k−1} + v_{k−1}·dt + ½·a·dt²,   v_k = v_{k−1} + a·dt
/// Biases are held constant.

#include <cstdint>

#include "swlio/core/types.h"
#include "swlio/estimator/frontend/deskew.h"

namespace swlio::estimator {

/// One interval of the formulas above: integrates `state` from its time to `sample.t_ns` with
/// the sample's values. Returns false, leaving `state` unchanged, when the sample is not newer
/// than the state.
bool StrapdownStep(double gravity_mps2, const ImuSample& sample, State* state);

class ImuPropagator {
 public:
  explicit ImuPropagator(double gravity_mps2) : gravity_mps2_(gravity_mps2) {}

  /// Restarts from `state` (its time and pose start a new track). The last sample seen is kept
  /// for ExtrapolateTo.
  void Reset(const State& state);
  /// Integrates up to the sample's time; samples not newer than the state are only remembered.
  void Add(const ImuSample& sample);
  /// Integrates further to `t_ns` holding the last sample's rates (no-op when not later).
  void ExtrapolateTo(int64_t t_ns);

  const State& state() const { return state_; }
  const PoseTrack& track() const { return track_; }

 private:
  double gravity_mps2_;
  State state_;
  ImuSample last_;
  bool have_last_ = false;
  PoseTrack track_;
};

}  // namespace swlio::estimator

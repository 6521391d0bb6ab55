#include "swlio/estimator/imu/imu_propagator.h"

#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

// The formulas of the header, over [state.t_ns, t_ns] with raw (not bias-corrected) rates.
void Integrate(double gravity_mps2,
               const Eigen::Vector3d& gyro_radps,
               const Eigen::Vector3d& acc_mps2,
               int64_t t_ns,
               State* state) {
  const double dt = NsToSec(t_ns - state->t_ns);
  const Eigen::Vector3d w = gyro_radps - state->bias_gyro;
  const Eigen::Vector3d f = acc_mps2 - state->bias_acc;
  const Eigen::Matrix3d R = state->T_world_imu.linear();
  const Eigen::Vector3d a =
      R * lie::Exp(0.5 * dt * w) * f + Eigen::Vector3d(0.0, 0.0, -gravity_mps2);
  state->T_world_imu.translation() += state->vel_world * dt + 0.5 * a * dt * dt;
  state->vel_world += a * dt;
  state->T_world_imu.linear() = R * lie::Exp(dt * w);
  state->t_ns = t_ns;
}

}  // namespace

bool StrapdownStep(double gravity_mps2, const ImuSample& sample, State* state) {
  if (sample.t_ns <= state->t_ns) return false;
  Integrate(gravity_mps2, sample.gyro_radps, sample.acc_mps2, sample.t_ns, state);
  return true;
}

void ImuPropagator::Reset(const State& state) {
  state_ = state;
  track_.Clear();
  track_.Add(state_.t_ns, state_.T_world_imu);
}

void ImuPropagator::Add(const ImuSample& sample) {
  if (StrapdownStep(gravity_mps2_, sample, &state_)) {
    track_.Add(state_.t_ns, state_.T_world_imu);
  }
  last_ = sample;
  have_last_ = true;
}

void ImuPropagator::ExtrapolateTo(int64_t t_ns) {
  if (!have_last_ || t_ns <= state_.t_ns) return;
  Integrate(gravity_mps2_, last_.gyro_radps, last_.acc_mps2, t_ns, &state_);
  track_.Add(state_.t_ns, state_.T_world_imu);
}

}  // namespace swlio::estimator

#include "swlio/estimator/imu_propagator.h"

#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {

void ImuPropagator::Reset(const State& state) {
  state_ = state;
  track_.Clear();
  track_.Add(state_.t_ns, state_.T_world_imu);
}

void ImuPropagator::Add(const ImuSample& sample) {
  if (sample.t_ns > state_.t_ns) {
    const Eigen::Vector3d gyro =
        have_last_ ? 0.5 * (sample.gyro_radps + last_.gyro_radps) : sample.gyro_radps;
    const Eigen::Vector3d acc =
        have_last_ ? 0.5 * (sample.acc_mps2 + last_.acc_mps2) : sample.acc_mps2;
    Step(gyro, acc, sample.t_ns);
  }
  last_ = sample;
  have_last_ = true;
}

void ImuPropagator::ExtrapolateTo(int64_t t_ns) {
  if (!have_last_ || t_ns <= state_.t_ns) return;
  Step(last_.gyro_radps, last_.acc_mps2, t_ns);
}

void ImuPropagator::Step(const Eigen::Vector3d& gyro_radps,
                         const Eigen::Vector3d& acc_mps2,
                         int64_t t_ns) {
  const double dt = NsToSec(t_ns - state_.t_ns);
  const Eigen::Vector3d w = gyro_radps - state_.bias_gyro;
  const Eigen::Vector3d f = acc_mps2 - state_.bias_acc;
  const Eigen::Matrix3d R = state_.T_world_imu.linear();
  const Eigen::Vector3d a =
      R * lie::Exp(0.5 * dt * w) * f + Eigen::Vector3d(0.0, 0.0, -gravity_mps2_);
  state_.T_world_imu.translation() += state_.vel_world * dt + 0.5 * a * dt * dt;
  state_.vel_world += a * dt;
  state_.T_world_imu.linear() = R * lie::Exp(dt * w);
  state_.t_ns = t_ns;
  track_.Add(t_ns, state_.T_world_imu);
}

}  // namespace swlio::estimator

#include "swlio/estimator/imu/imu_interval_means.h"

namespace swlio::estimator {

ImuSample ImuIntervalMeans::Next(const ImuSample& instant) {
  ImuSample out = instant;
  if (previous_ && previous_->t_ns < instant.t_ns) {
    out.acc_mps2 = 0.5 * (previous_->acc_mps2 + instant.acc_mps2);
    out.gyro_radps = 0.5 * (previous_->gyro_radps + instant.gyro_radps);
  }
  previous_ = instant;
  return out;
}

}  // namespace swlio::estimator

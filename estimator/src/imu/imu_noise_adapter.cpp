#include "swlio/estimator/imu/imu_noise_adapter.h"

#include <algorithm>
#include <cmath>

#include "swlio/core/time.h"

namespace swlio::estimator {

ConfigIssues ImuNoiseAdapterConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "gain", gain, 0.0, 10.0);
  CheckInRange(issues, "time_constant_s", time_constant_s, 0.1, 600.0);
  return issues;
}

ImuNoiseAdapter::ImuNoiseAdapter(const ImuNoiseConfig& datasheet,
                                 const ImuNoiseAdapterConfig& config)
    : datasheet_(datasheet), config_(config) {}

void ImuNoiseAdapter::Add(const ImuSample& sample) {
  if (seen_ > 0 && sample.t_ns <= prev_.t_ns) {  // time went back or stood: start over
    seen_ = 0;
    weight_s_ = 0.0;
  }
  if (seen_ >= 2) {
    const double dt_s = NsToSec(sample.t_ns - prev_.t_ns);
    const double alpha = std::min(1.0, dt_s / config_.time_constant_s);
    const double acc2 =
        (sample.acc_mps2 - 2.0 * prev_.acc_mps2 + prev2_.acc_mps2).squaredNorm() / 18.0;
    const double gyro2 =
        (sample.gyro_radps - 2.0 * prev_.gyro_radps + prev2_.gyro_radps).squaredNorm() / 18.0;
    if (weight_s_ == 0.0) {
      acc_var_ = acc2;
      gyro_var_ = gyro2;
      dt_s_ = dt_s;
    }
    acc_var_ += alpha * (acc2 - acc_var_);
    gyro_var_ += alpha * (gyro2 - gyro_var_);
    dt_s_ += alpha * (dt_s - dt_s_);
    weight_s_ += dt_s;
  }
  prev2_ = prev_;
  prev_ = sample;
  seen_ = std::min(seen_ + 1, 2);
}

double ImuNoiseAdapter::acc_density_mps2_per_sqrthz() const {
  return std::sqrt(acc_var_ * dt_s_);  // σ / √f_s
}

double ImuNoiseAdapter::gyro_density_radps_per_sqrthz() const {
  return std::sqrt(gyro_var_ * dt_s_);
}

ImuNoiseConfig ImuNoiseAdapter::Effective() const {
  if (!config_.enabled || weight_s_ < 1.0) return datasheet_;
  ImuNoiseConfig out = datasheet_;
  const double g = config_.gain;
  out.acc_noise_density_mps2_per_sqrthz =
      std::hypot(datasheet_.acc_noise_density_mps2_per_sqrthz, g * acc_density_mps2_per_sqrthz());
  out.gyro_noise_density_radps_per_sqrthz = std::hypot(
      datasheet_.gyro_noise_density_radps_per_sqrthz, g * gyro_density_radps_per_sqrthz());
  return out;
}

}  // namespace swlio::estimator

#include "sensors/imu_temperature.h"

#include <algorithm>
#include <cmath>

namespace swlio::sim {

double ImuTemperatureC(const ImuTemperatureConfig& config, double t_s) {
  const double tau = std::max(config.time_constant_s, 1e-9);
  return config.start_c + config.rise_c * (1.0 - std::exp(-std::max(t_s, 0.0) / tau));
}

Eigen::Vector3d ImuTemperatureGyroBias(const ImuTemperatureConfig& config, double t_s) {
  if (!config.on) return Eigen::Vector3d::Zero();
  return config.gyro_bias_per_c * (ImuTemperatureC(config, t_s) - config.start_c);
}

Eigen::Vector3d ImuTemperatureAccBias(const ImuTemperatureConfig& config, double t_s) {
  if (!config.on) return Eigen::Vector3d::Zero();
  return config.acc_bias_per_c * (ImuTemperatureC(config, t_s) - config.start_c);
}

}  // namespace swlio::sim

#pragma once
/// @file
/// IMU bias drift with temperature (the `temperature` disturbance, issue 36): the device warms
/// up after a cold start, T(t) = T0 + ΔT·(1 − exp(−t/τ)), and each axis's bias moves by its own
/// coefficient times T(t) − T0, on top of the random walk of ImuNoiseModel.

#include <Eigen/Core>

namespace swlio::sim {

struct ImuTemperatureConfig {
  bool on = false;
  double start_c = 5.0;  ///< T0: a cold morning start
  /// ΔT: the electronics and the sun on the housing (+10–20 °C; issue 36).
  double rise_c = 15.0;
  /// τ: Xsens asks for 5 min, preferably 10 min or more, of warm-up before the gyro bias is
  /// estimated, because "gyro bias may change during the warm up period" (Xsens knowledge
  /// base, "Bias repeatability of gyroscopes").
  double time_constant_s = 300.0;
  Eigen::Vector3d gyro_bias_per_c = Eigen::Vector3d::Zero();  ///< rad/s per °C, per axis
  Eigen::Vector3d acc_bias_per_c = Eigen::Vector3d::Zero();   ///< m/s² per °C, per axis
};

/// The device's temperature at host time `t_s` (°C).
double ImuTemperatureC(const ImuTemperatureConfig& config, double t_s);

/// The bias the temperature adds at `t_s` (zero when off).
Eigen::Vector3d ImuTemperatureGyroBias(const ImuTemperatureConfig& config, double t_s);
Eigen::Vector3d ImuTemperatureAccBias(const ImuTemperatureConfig& config, double t_s);

}  // namespace swlio::sim

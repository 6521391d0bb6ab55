// The IMU noise measured from the data (imu_noise_adapter.h; off by default): when on, a quiet
// MTi keeps its datasheet densities, a vibrating chassis loosens them, slow motion does not.

#include "swlio/estimator/imu/imu_noise_adapter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace swlio::estimator {
namespace {

/// 10 s at 400 Hz: white noise of the datasheet's density plus `vibration_rms` (m/s², at 23
/// and 61 Hz) and a slow 0.5 Hz manoeuvre of 1 m/s² and 0.5 rad/s.
ImuNoiseAdapter Feed(double vibration_rms, const ImuNoiseConfig& datasheet) {
  ImuNoiseAdapterConfig on;
  on.enabled = true;
  ImuNoiseAdapter adapter(datasheet, on);
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  const double acc_sigma = datasheet.acc_noise_density_mps2_per_sqrthz * std::sqrt(400.0);
  const double gyro_sigma = datasheet.gyro_noise_density_radps_per_sqrthz * std::sqrt(400.0);
  for (int k = 0; k < 4000; ++k) {
    const double t = k / 400.0;
    ImuSample s;
    s.t_ns = static_cast<int64_t>(k) * 2'500'000;
    const double slow = std::sin(2 * M_PI * 0.5 * t);
    const double shake =
        vibration_rms * (std::sin(2 * M_PI * 23 * t) + std::sin(2 * M_PI * 61 * t + 1.0));
    for (int i = 0; i < 3; ++i) {
      s.acc_mps2[i] = slow + shake + acc_sigma * n01(rng);
      s.gyro_radps[i] = 0.5 * slow + 0.02 * shake + gyro_sigma * n01(rng);
    }
    s.acc_mps2.z() += 9.81;
    adapter.Add(s);
  }
  return adapter;
}

TEST(ImuNoiseAdapter, QuietImuKeepsTheDatasheet) {
  const ImuNoiseConfig datasheet;
  const ImuNoiseAdapter a = Feed(0.0, datasheet);
  EXPECT_NEAR(a.acc_density_mps2_per_sqrthz() / datasheet.acc_noise_density_mps2_per_sqrthz, 1.0,
              0.1);
  EXPECT_NEAR(a.gyro_density_radps_per_sqrthz() / datasheet.gyro_noise_density_radps_per_sqrthz,
              1.0, 0.1);
  EXPECT_LT(a.Effective().acc_noise_density_mps2_per_sqrthz,
            1.1 * datasheet.acc_noise_density_mps2_per_sqrthz);
  EXPECT_EQ(a.Effective().acc_bias_random_walk_mps3_per_sqrthz,
            datasheet.acc_bias_random_walk_mps3_per_sqrthz);
}

TEST(ImuNoiseAdapter, VibrationLoosensTheDensities) {
  const ImuNoiseConfig datasheet;
  const ImuNoiseAdapter a = Feed(1.0, datasheet);
  EXPECT_GT(a.Effective().acc_noise_density_mps2_per_sqrthz,
            3.0 * datasheet.acc_noise_density_mps2_per_sqrthz);
  EXPECT_GT(a.Effective().gyro_noise_density_radps_per_sqrthz,
            1.1 * datasheet.gyro_noise_density_radps_per_sqrthz);
  ImuNoiseAdapter disabled(datasheet, ImuNoiseAdapterConfig{});  // the default: off
  EXPECT_EQ(disabled.Effective().acc_noise_density_mps2_per_sqrthz,
            datasheet.acc_noise_density_mps2_per_sqrthz);
  ImuNoiseAdapterConfig bad;
  bad.gain = -1.0;
  EXPECT_FALSE(bad.Validate().empty());
}

}  // namespace
}  // namespace swlio::estimator

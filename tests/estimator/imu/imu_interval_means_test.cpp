// Instantaneous samples as interval means (imu_interval_means.h): the trapezoidal mean of each
// pair, which the pre-integration's scheme then integrates as the midpoint rule did.

#include "swlio/estimator/imu/imu_interval_means.h"

#include <gtest/gtest.h>

#include <vector>

#include "swlio/core/time.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {
namespace {

ImuSample At(int64_t t_ns, double gyro_z, double acc_z) {
  ImuSample s;
  s.t_ns = t_ns;
  s.gyro_radps = Eigen::Vector3d(0.0, 0.0, gyro_z);
  s.acc_mps2 = Eigen::Vector3d(0.0, 0.0, acc_z);
  return s;
}

TEST(ImuIntervalMeans, AveragesEachSampleWithTheOneBefore) {
  ImuIntervalMeans means;
  const ImuSample first = means.Next(At(0, 1.0, 10.0));
  EXPECT_EQ(first.gyro_radps.z(), 1.0);  // nothing before: as it is
  const ImuSample second = means.Next(At(2'500'000, 3.0, 20.0));
  EXPECT_EQ(second.t_ns, 2'500'000);
  EXPECT_DOUBLE_EQ(second.gyro_radps.z(), 2.0);
  EXPECT_DOUBLE_EQ(second.acc_mps2.z(), 15.0);
  // A sample not newer restarts the pairing: as it is, and the next one pairs with it.
  EXPECT_EQ(means.Next(At(2'500'000, 7.0, 0.0)).gyro_radps.z(), 7.0);
  EXPECT_DOUBLE_EQ(means.Next(At(5'000'000, 9.0, 0.0)).gyro_radps.z(), 8.0);
}

// A rate and a specific force linear in time, sampled at their stamps: the trapezoidal means are
// the exact means, so integrating them between samples is exact.
TEST(ImuIntervalMeans, LinearMotionIntegratesExactlyBetweenSamples) {
  ImuIntervalMeans means;
  std::vector<ImuSample> samples;
  for (int k = 0; k <= 40; ++k) {
    const double t = k * 0.0025;
    samples.push_back(means.Next(At(SecToNs(t), 0.2 + t, 1.0 + 2.0 * t)));
  }
  Preintegrator pre(ImuNoiseConfig{}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const double t0 = 0.01, t1 = 0.09;
  ASSERT_EQ(pre.Integrate(samples, SecToNs(t0), SecToNs(t1)), PreintegrationStatus::kOk);
  const double angle = 0.2 * (t1 - t0) + 0.5 * (t1 * t1 - t0 * t0);
  EXPECT_NEAR(pre.result().delta_R(1, 0), std::sin(angle), 1e-12);
  EXPECT_NEAR(pre.result().delta_v.z(), (t1 - t0) + (t1 * t1 - t0 * t0), 1e-12);
}

}  // namespace
}  // namespace swlio::estimator

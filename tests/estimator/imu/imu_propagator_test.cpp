// ImuPropagator against closed-form motions: a level turn on a circle at constant speed, and a
// straight constant acceleration; plus bias handling and the recorded pose track.

#include "swlio/estimator/imu/imu_propagator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

constexpr double kG = 9.80665;
constexpr int64_t kStepNs = 2'500'000;  // 400 Hz

ImuSample Sample(int64_t t_ns, const Eigen::Vector3d& gyro, const Eigen::Vector3d& acc) {
  ImuSample s;
  s.t_ns = t_ns;
  s.gyro_radps = gyro;
  s.acc_mps2 = acc;
  return s;
}

TEST(ImuPropagator, LevelCircleAtConstantSpeed) {
  constexpr double kSpeed = 1.5, kYawRate = 1.0;  // 1.5 m/s, 57 °/s: the fast case
  ImuPropagator prop(kG);
  State start;
  start.vel_world = Eigen::Vector3d(kSpeed, 0.0, 0.0);
  prop.Reset(start);
  // Body frame: turning left, the centripetal acceleration v·ω points to +y.
  const Eigen::Vector3d gyro(0.0, 0.0, kYawRate), acc(0.0, kSpeed * kYawRate, kG);
  for (int64_t t = 0; t <= 2 * kNsPerSec; t += kStepNs) prop.Add(Sample(t, gyro, acc));
  const double t = 2.0;
  const Eigen::Vector3d expected(kSpeed / kYawRate * std::sin(kYawRate * t),
                                 kSpeed / kYawRate * (1.0 - std::cos(kYawRate * t)), 0.0);
  EXPECT_LT((prop.state().T_world_imu.translation() - expected).norm(), 2e-3);
  EXPECT_NEAR(lie::RpyFromRotation(prop.state().T_world_imu.linear()).z(), kYawRate * t, 1e-9);
  EXPECT_NEAR(prop.state().vel_world.norm(), kSpeed, 1e-3);
  EXPECT_EQ(prop.state().t_ns, 2 * kNsPerSec);
}

TEST(ImuPropagator, BiasesAreRemovedAndExtrapolationHoldsTheLastRates) {
  ImuPropagator prop(kG);
  State start;
  start.bias_acc = Eigen::Vector3d(0.1, -0.2, 0.05);
  start.bias_gyro = Eigen::Vector3d(0.01, 0.0, -0.02);
  prop.Reset(start);
  const Eigen::Vector3d acc = Eigen::Vector3d(0.5, 0.0, kG) + start.bias_acc;
  for (int64_t t = 0; t <= kNsPerSec; t += kStepNs) {
    prop.Add(Sample(t, start.bias_gyro, acc));
  }
  prop.ExtrapolateTo(2 * kNsPerSec);  // one more second at the same specific force
  EXPECT_NEAR(prop.state().T_world_imu.translation().x(), 0.5 * 0.5 * 4.0, 1e-9);
  EXPECT_NEAR(prop.state().vel_world.x(), 1.0, 1e-9);
  EXPECT_LT(prop.state().T_world_imu.translation().tail<2>().norm(), 1e-9);
  EXPECT_TRUE(prop.state().T_world_imu.linear().isIdentity(1e-12));
}

TEST(ImuPropagator, TrackHasOnePosePerSampleAndInterpolates) {
  ImuPropagator prop(kG);
  prop.Reset(State{});
  const Eigen::Vector3d gyro(0.0, 0.0, 0.0), acc(2.0, 0.0, kG);
  for (int64_t t = kStepNs; t <= 10 * kStepNs; t += kStepNs) prop.Add(Sample(t, gyro, acc));
  EXPECT_EQ(prop.track().begin_ns(), 0);
  EXPECT_EQ(prop.track().end_ns(), 10 * kStepNs);
  Eigen::Isometry3d T;
  ASSERT_TRUE(prop.track().At(5 * kStepNs, &T));
  EXPECT_NEAR(T.translation().x(), 0.5 * 2.0 * std::pow(NsToSec(5 * kStepNs), 2), 1e-12);
  EXPECT_FALSE(prop.track().At(11 * kStepNs, &T));
  // A sample not newer than the state is remembered, not integrated.
  prop.Add(Sample(3 * kStepNs, gyro, acc));
  EXPECT_EQ(prop.state().t_ns, 10 * kStepNs);
}

}  // namespace
}  // namespace swlio::estimator

// DivergenceMonitor: each check trips on its own bound, the sweep counts need that many sweeps
// in a row, and a believable state never trips.

#include "swlio/estimator/window/divergence_monitor.h"

#include <gtest/gtest.h>

#include <limits>

namespace swlio::estimator {
namespace {

SweepCheck Believable() {
  SweepCheck c;
  c.state.vel_world = Eigen::Vector3d(1.5, 0.2, 0.0);
  c.state.bias_acc = Eigen::Vector3d(0.05, -0.03, 0.02);
  c.state.bias_gyro = Eigen::Vector3d(0.002, 0.001, -0.003);
  c.prediction_error_m = 0.05;
  c.prediction_error_rad = 0.005;
  return c;
}

TEST(DivergenceMonitor, ABelievableStateNeverTrips) {
  DivergenceMonitor m{DivergenceConfig{}};
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(m.Check(Believable()), DivergenceReason::kNone);
}

TEST(DivergenceMonitor, EachStateBoundTripsAtOnce) {
  DivergenceMonitor m{DivergenceConfig{}};
  SweepCheck c = Believable();
  c.state.vel_world = Eigen::Vector3d(4.0, 3.5, 0.0);  // 5.3 m/s
  EXPECT_EQ(m.Check(c), DivergenceReason::kSpeed);
  c = Believable();
  c.state.bias_acc.z() = 1.2;
  EXPECT_EQ(m.Check(c), DivergenceReason::kBiasAcc);
  c = Believable();
  c.state.bias_gyro.x() = -0.2;
  EXPECT_EQ(m.Check(c), DivergenceReason::kBiasGyro);
}

TEST(DivergenceMonitor, ANonFiniteStateTrips) {
  DivergenceMonitor m{DivergenceConfig{}};
  SweepCheck c = Believable();
  c.state.vel_world.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(m.Check(c), DivergenceReason::kSpeed);
}

TEST(DivergenceMonitor, LidarLostNeedsThatManyFailedSweepsInARow) {
  DivergenceConfig config;
  config.max_failed_sweeps = 5;
  DivergenceMonitor m(config);
  SweepCheck failed = Believable();
  failed.match_failed = true;
  failed.prediction_error_m = -1.0;
  for (int i = 0; i < 4; ++i) ASSERT_EQ(m.Check(failed), DivergenceReason::kNone);
  EXPECT_EQ(m.Check(Believable()), DivergenceReason::kNone) << "a good sweep starts over";
  for (int i = 0; i < 4; ++i) ASSERT_EQ(m.Check(failed), DivergenceReason::kNone);
  EXPECT_EQ(m.Check(failed), DivergenceReason::kLidarLost);
  EXPECT_EQ(m.Check(failed), DivergenceReason::kNone) << "the count starts over after a trip";
}

TEST(DivergenceMonitor, DisagreementNeedsThatManyRegisteredSweepsInARow) {
  DivergenceConfig config;
  config.max_inconsistent_sweeps = 3;
  DivergenceMonitor m(config);
  SweepCheck far = Believable();
  far.prediction_error_m = 2.0;
  SweepCheck turned = Believable();
  turned.prediction_error_rad = 0.5;
  SweepCheck unregistered = Believable();
  unregistered.prediction_error_m = unregistered.prediction_error_rad = -1.0;
  EXPECT_EQ(m.Check(far), DivergenceReason::kNone);
  EXPECT_EQ(m.Check(unregistered), DivergenceReason::kNone) << "no registration: no evidence";
  EXPECT_EQ(m.Check(turned), DivergenceReason::kNone);
  EXPECT_EQ(m.Check(far), DivergenceReason::kInconsistent);
  EXPECT_EQ(m.Check(far), DivergenceReason::kNone);
  EXPECT_EQ(m.Check(Believable()), DivergenceReason::kNone);
  EXPECT_EQ(m.Check(far), DivergenceReason::kNone) << "an agreeing sweep starts over";
}

TEST(DivergenceMonitor, DisabledReportsNothing) {
  DivergenceConfig config;
  config.enabled = false;
  DivergenceMonitor m(config);
  SweepCheck c = Believable();
  c.state.vel_world.x() = 100.0;
  EXPECT_EQ(m.Check(c), DivergenceReason::kNone);
}

TEST(DivergenceConfig, ValidateNamesTheBadKeys) {
  DivergenceConfig config;
  EXPECT_TRUE(config.Validate().empty());
  config.max_speed_mps = 0.0;
  config.max_failed_sweeps = 0;
  const ConfigIssues issues = config.Validate();
  ASSERT_EQ(issues.size(), 2u);
  EXPECT_EQ(issues[0].key, "max_speed_mps");
  EXPECT_EQ(issues[1].key, "max_failed_sweeps");
}

}  // namespace
}  // namespace swlio::estimator

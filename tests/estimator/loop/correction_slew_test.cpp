// CorrectionSlew: a new map correction reaches the output at a bounded rate, measured at the
// robot (not at the map origin), and is followed to the end.
#include "swlio/estimator/loop/correction_slew.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

Eigen::Isometry3d Pose(const Eigen::Vector3d& p, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::Exp(Eigen::Vector3d(0.0, 0.0, yaw));
  T.translation() = p;
  return T;
}

constexpr int64_t kStepNs = 2'500'000;  // 400 Hz output

/// Steps the slew for `seconds` of output of a robot standing at `T_odom_imu`; returns the
/// largest output motion per step (m, rad) and leaves the last output in `last`.
std::pair<double, double> StepFor(CorrectionSlew* slew,
                                  const Eigen::Isometry3d& T_odom_imu,
                                  int64_t* t_ns,
                                  double seconds,
                                  Eigen::Isometry3d* last) {
  double max_m = 0.0, max_rad = 0.0;
  Eigen::Isometry3d prev = slew->current() * T_odom_imu;
  for (int64_t end = *t_ns + static_cast<int64_t>(seconds * 1e9); *t_ns < end; *t_ns += kStepNs) {
    const Eigen::Isometry3d out = slew->Step(*t_ns, T_odom_imu) * T_odom_imu;
    const Eigen::Isometry3d d = prev.inverse() * out;
    max_m = std::max(max_m, d.translation().norm());
    max_rad = std::max(max_rad, Eigen::AngleAxisd(d.rotation()).angle());
    prev = out;
  }
  *last = prev;
  return {max_m, max_rad};
}

TEST(CorrectionSlew, ATranslationIsFollowedAtTheRate) {
  CorrectionSlew slew({.max_rate_mps = 0.2, .max_rate_radps = 0.05});
  const Eigen::Isometry3d T_odom_imu = Pose({30.0, -5.0, 0.5}, 1.0);
  int64_t t_ns = 1'000'000'000;
  slew.Step(t_ns, T_odom_imu);
  EXPECT_TRUE(slew.settled());
  slew.SetTarget(Pose({1.0, 0.0, 0.0}, 0.0));  // 1 m
  EXPECT_FALSE(slew.settled());
  Eigen::Isometry3d out;
  auto [m, rad] = StepFor(&slew, T_odom_imu, &t_ns, 2.0, &out);
  EXPECT_LE(m, 0.2 * 2.5e-3 + 1e-9);  // per 2.5 ms step
  const double moved = (out.translation() - T_odom_imu.translation()).norm();
  EXPECT_NEAR(moved, 0.4, 0.002);  // 2 s at 0.2 m/s
  StepFor(&slew, T_odom_imu, &t_ns, 3.1, &out);
  EXPECT_TRUE(slew.settled());
  EXPECT_TRUE(slew.current().isApprox(slew.target(), 1e-12));
}

// A 0.1 rad correction about the map origin seen by a robot 200 m away is a 20 m jump of its
// output if applied at once; slewed, the output moves at ≤ 0.2 m/s and ≤ 0.05 rad/s.
TEST(CorrectionSlew, ARotationFarFromTheOriginMovesTheOutputAtTheRateToo) {
  CorrectionSlew slew({.max_rate_mps = 0.2, .max_rate_radps = 0.05});
  const Eigen::Isometry3d T_odom_imu = Pose({200.0, 10.0, 0.5}, 0.3);
  int64_t t_ns = 0;
  slew.Step(t_ns, T_odom_imu);
  slew.SetTarget(Pose({0.0, 0.0, 0.0}, 0.1));
  Eigen::Isometry3d out;
  const auto [m, rad] = StepFor(&slew, T_odom_imu, &t_ns, 10.0, &out);
  std::printf("[ slew ] per 2.5 ms step: at most %.2e m, %.2e rad\n", m, rad);
  EXPECT_LE(m, 0.2 * 2.5e-3 * 1.01);
  EXPECT_LE(rad, 0.05 * 2.5e-3 * 1.01);
  EXPECT_FALSE(slew.settled());  // 20 m at 0.2 m/s takes 100 s
  StepFor(&slew, T_odom_imu, &t_ns, 101.0, &out);
  EXPECT_TRUE(slew.settled());
  EXPECT_TRUE(out.isApprox(slew.target() * T_odom_imu, 1e-9));
}

TEST(CorrectionSlew, TimeGoingBackDoesNotMoveIt) {
  CorrectionSlew slew({.max_rate_mps = 0.2, .max_rate_radps = 0.05});
  const Eigen::Isometry3d T = Pose({1.0, 2.0, 0.0}, 0.0);
  slew.Step(5'000'000'000, T);
  slew.SetTarget(Pose({1.0, 0.0, 0.0}, 0.0));
  const Eigen::Isometry3d before = slew.current();
  slew.Step(4'000'000'000, T);  // an older output (odometry lags the IMU-rate pose)
  EXPECT_TRUE(slew.current().isApprox(before, 0.0));
  slew.Step(5'500'000'000, T);  // half a second later than the newest: 0.1 m
  EXPECT_NEAR(slew.current().translation().x(), 0.1, 1e-9);
}

}  // namespace
}  // namespace swlio::estimator

// Wheel-odometry velocity factor (wheel_velocity_factor.h): residual at a known state, analytic
// Jacobians against central differences, refusal of bad input.

#include "swlio/estimator/wheel/wheel_velocity_factor.h"

#include <gtest/gtest.h>

#include "jacobian_check.h"
#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

Eigen::Isometry3d Pose(const Vec3& p, const Vec3& rotation_vector) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::Exp(rotation_vector);
  T.translation() = p;
  return T;
}

std::vector<double> PoseBlock(const Eigen::Isometry3d& T) {
  std::vector<double> x(kPoseSize);
  PoseToParameters(T, x.data());
  return x;
}

std::vector<double> SpeedBias(const Vec3& v, const Vec3& b_g) {
  std::vector<double> sb(kSpeedBiasSize, 0.0);
  for (int i = 0; i < 3; ++i) {
    sb[static_cast<size_t>(kSbVel + i)] = v[i];
    sb[static_cast<size_t>(kSbBiasGyro + i)] = b_g[i];
  }
  return sb;
}

TEST(WheelVelocityFactor, ZeroResidualForTheTrueMotion) {
  // Robot heading 30° left of world x at 1.2 m/s, turning at 0.3 rad/s; IMU mounted 0.4 m ahead
  // of and 0.3 m above the base, yawed 90° (IMU x = base y).
  const Eigen::Isometry3d T_imu_base = Pose({-0.4, 0.0, -0.3}, {0.0, 0.0, -M_PI / 2});
  const Eigen::Isometry3d T_world_base = Pose({5.0, 2.0, 0.1}, {0.0, 0.0, M_PI / 6});
  const Eigen::Isometry3d T_world_imu = T_world_base * T_imu_base.inverse();
  const Vec3 omega_world(0.0, 0.0, 0.3);
  const Vec3 v_base_world = T_world_base.linear() * Vec3(1.2, 0.0, 0.0);
  // The IMU's velocity: the base's plus ω × (p_imu − p_base).
  const Vec3 v_imu_world =
      v_base_world + omega_world.cross(T_world_imu.translation() - T_world_base.translation());
  const Vec3 gyro = T_world_imu.linear().transpose() * omega_world;
  const Vec3 b_g(0.001, -0.002, 0.003);
  auto f = WheelVelocityFactor::Create(1.2, gyro + b_g, T_imu_base, {});
  ASSERT_NE(f, nullptr);
  const std::vector<double> pose = PoseBlock(T_world_imu), sb = SpeedBias(v_imu_world, b_g);
  EXPECT_LT((f->BaseVelocity(pose.data(), sb.data()) - Vec3(1.2, 0.0, 0.0)).norm(), 1e-12);
  // A 0.1 m/s error in the measured speed is 2 σ (σ_forward 0.05) on the first residual.
  auto g = WheelVelocityFactor::Create(1.3, gyro + b_g, T_imu_base, {});
  const double* blocks[2] = {pose.data(), sb.data()};
  Vec3 r;
  ASSERT_TRUE(g->Evaluate(blocks, r.data(), nullptr));
  EXPECT_NEAR(r.x(), -2.0, 1e-9);
  EXPECT_NEAR(r.tail<2>().norm(), 0.0, 1e-9);
}

TEST(WheelVelocityFactor, JacobiansMatchNumeric) {
  const Eigen::Isometry3d T_imu_base = Pose({-0.4, 0.1, -0.3}, {0.02, -0.03, 0.4});
  auto f =
      WheelVelocityFactor::Create(0.8, {0.05, -0.1, 0.4}, T_imu_base,
                                  {.forward_mps = 0.05, .lateral_mps = 0.1, .vertical_mps = 0.2});
  ASSERT_NE(f, nullptr);
  const PoseManifold pose;
  const test::JacobianErrors e =
      test::CheckJacobians(*f,
                           {PoseBlock(Pose({1.0, -2.0, 0.5}, {0.1, -0.2, 1.0})),
                            SpeedBias({0.7, 0.3, -0.05}, {0.01, 0.02, -0.01})},
                           {&pose, nullptr});
  EXPECT_LT(e.Worst(), 1e-7);
}

TEST(WheelVelocityFactor, RefusesBadInput) {
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_EQ(WheelVelocityFactor::Create(std::nan(""), Vec3::Zero(), I, {}), nullptr);
  EXPECT_EQ(WheelVelocityFactor::Create(1.0, Vec3(0, 0, INFINITY), I, {}), nullptr);
  EXPECT_EQ(WheelVelocityFactor::Create(1.0, Vec3::Zero(), I, {.forward_mps = 0.0}), nullptr);
}

}  // namespace
}  // namespace swlio::estimator

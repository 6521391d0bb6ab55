// Standstill detection and the zero-velocity factor (standstill.h): what counts as rest, the
// factor's Jacobian, and a window at rest where the LiDAR sees too little to hold the pose.

#include "swlio/estimator/window/standstill.h"

#include "swlio/estimator/imu/imu_stillness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>

#include "jacobian_check.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/window/window_estimator.h"
#include "synthetic_scan.h"
#include "wall_sweep.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kG = 9.80665;

/// 200 samples (0.5 s at 400 Hz, StandstillConfig::imu_window_s) of an IMU at rest with
/// attitude R (against gravity), biases and the MTi-G-710's white noise (0.012 m/s², 0.0035
/// rad/s per sample); `acc_world` and `rate` add a motion.
std::vector<ImuSample> Interval(const Eigen::Matrix3d& R,
                                const Vec3& b_a,
                                const Vec3& b_g,
                                const Vec3& acc_world = Vec3::Zero(),
                                const Vec3& rate = Vec3::Zero()) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  std::vector<ImuSample> out;
  for (int i = 0; i < 200; ++i) {
    ImuSample s;
    s.t_ns = i * 2'500'000;
    s.acc_mps2 = R.transpose() * (acc_world + Vec3(0.0, 0.0, kG)) + b_a;
    s.gyro_radps = rate + b_g;
    for (int k = 0; k < 3; ++k) s.acc_mps2(k) += 0.012 * n01(rng);
    for (int k = 0; k < 3; ++k) s.gyro_radps(k) += 0.0035 * n01(rng);
    out.push_back(s);
  }
  return out;
}

TEST(ImuAtRest, RestWithATiltAndBiasesIsRest) {
  const Eigen::Matrix3d R = lie::Exp(Vec3(0.1, -0.05, 2.0));
  const Vec3 b_a(0.03, -0.02, 0.01), b_g(0.002, -0.001, 0.003);
  EXPECT_TRUE(ImuAtRest(Interval(R, b_a, b_g), R, b_a, b_g, kG, {}));
}

TEST(ImuAtRest, AccelerationTurningAndVibrationAreNotRest) {
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  const Vec3 zero = Vec3::Zero();
  const StandstillConfig c;
  // A gentle start (0.1 m/s², twice the limit) and a slow turn (0.6 °/s).
  EXPECT_FALSE(ImuAtRest(Interval(R, zero, zero, Vec3(0.1, 0.0, 0.0)), R, zero, zero, kG, c));
  EXPECT_FALSE(
      ImuAtRest(Interval(R, zero, zero, zero, Vec3(0.0, 0.0, 0.01)), R, zero, zero, kG, c));
  // A push: 0.3 m/s² forward, then back, 0.04 m/s at the most (the mean stays zero).
  std::vector<ImuSample> pushed = Interval(R, zero, zero);
  for (size_t i = 0; i < pushed.size(); ++i) {
    pushed[i].acc_mps2.x() += (i < 50 || i >= 150 ? -0.15 : 0.15);
  }
  EXPECT_FALSE(ImuAtRest(pushed, R, zero, zero, kG, c));
  // The attitude the test compares against matters: rest read with a 1° tilt error is not rest.
  EXPECT_FALSE(
      ImuAtRest(Interval(R, zero, zero), lie::Exp(Vec3(0.0175, 0.0, 0.0)), zero, zero, kG, c));
  // Too few samples to judge.
  std::vector<ImuSample> few = Interval(R, zero, zero);
  few.resize(3);
  EXPECT_FALSE(ImuAtRest(few, R, zero, zero, kG, c));
}

/// Motors idling shake the chassis at 15–80 Hz with 0.5–2 m/s² RMS (issue 36): that is rest,
/// and the zero-velocity factor's σ grows to the velocity's measured spread.
TEST(ImuAtRest, ChassisVibrationIsRest) {
  const Eigen::Matrix3d R = lie::Exp(Vec3(0.02, -0.01, 1.0));
  const Vec3 b_a(0.02, 0.01, -0.01), b_g(0.001, 0.0, -0.002);
  const StandstillConfig c;
  for (const double rms : {0.5, 1.0, 2.0}) {
    std::vector<ImuSample> shaking = Interval(R, b_a, b_g);
    for (ImuSample& s : shaking) {
      const double t = NsToSec(s.t_ns);
      // Three tones (16.3, 41 and 73 Hz) with the power split 0.6 / 0.25 / 0.15, mostly
      // vertical, and an angular part of 0.02 rad/s per m/s².
      const double tone = std::sqrt(1.2) * std::sin(2 * M_PI * 16.3 * t + 0.3) +
                          std::sqrt(0.5) * std::sin(2 * M_PI * 41.0 * t + 1.1) +
                          std::sqrt(0.3) * std::sin(2 * M_PI * 73.0 * t + 2.0);
      s.acc_mps2 += rms * tone * Vec3(0.45, 0.45, 0.77);
      s.gyro_radps += 0.02 * rms * tone * Vec3(0.67, 0.67, 0.32);
    }
    const std::optional<double> sigma = ImuAtRest(shaking, R, b_a, b_g, kG, c);
    const ImuStillness still = ComputeImuStillness(shaking);
    std::cout << rms << " m/s² RMS: raw std " << still.acc_std_mps2 << " m/s², low-passed "
              << still.acc_lowpass_std_mps2 << " m/s² and " << still.gyro_lowpass_std_radps
              << " rad/s; velocity spread " << still.velocity_rms_mps << " m/s\n";
    ASSERT_TRUE(sigma) << rms << " m/s² RMS";
    EXPECT_LT(*sigma, 0.03) << rms;
    if (rms == 2.0) {
      EXPECT_GT(*sigma, c.sigma_velocity_mps) << "the spread is measured";
    }
  }
}

TEST(ZeroVelocityFactor, ResidualAndJacobian) {
  const ZeroVelocityFactor f(0.005);
  std::vector<double> sb(kSpeedBiasSize, 0.1);
  sb[kSbVel] = 0.01;
  sb[kSbVel + 1] = -0.02;
  sb[kSbVel + 2] = 0.005;
  const double* blocks[1] = {sb.data()};
  Vec3 r;
  ASSERT_TRUE(f.Evaluate(blocks, r.data(), nullptr));
  EXPECT_LT((r - Vec3(2.0, -4.0, 1.0)).norm(), 1e-12);
  EXPECT_LT(swlio::test::CheckJacobians(f, {sb}, {nullptr}).Worst(), 1e-9);
}

TEST(StandstillConfig, ValidateNamesTheBadKeys) {
  StandstillConfig c;
  EXPECT_TRUE(c.Validate().empty());
  c.sigma_velocity_mps = 0.0;
  c.max_lidar_speed_mps = -1.0;
  const ConfigIssues issues = c.Validate();
  ASSERT_EQ(issues.size(), 2u);
  EXPECT_EQ(issues[0].key, "max_lidar_speed_mps");
  EXPECT_EQ(issues[1].key, "sigma_velocity_mps");
}

/// A sweep in a corridor along x (walls at y = ±3 m, ground 0.6 m below): every plane
/// contains x, so the scan says nothing about motion along the corridor.
Scan CorridorSweep(int64_t t_start_ns) {
  Scan scan;
  scan.t_start_ns = t_start_ns;
  scan.t_end_ns = t_start_ns + 99 * kNsPerMs;
  for (int column = 0; column < 1800; column += 2) {
    for (int ring = 0; ring < 16; ++ring) {
      LidarPoint p = test::At(ring, column, 1.0);
      const Eigen::Vector3d d = p.xyz_m.cast<double>();
      double range = 60.0;
      if (d.y() > 1e-6) range = std::min(range, 3.0 / d.y());
      if (d.y() < -1e-6) range = std::min(range, -3.0 / d.y());
      if (d.z() < -1e-6) range = std::min(range, -0.6 / d.z());
      if (range >= 60.0) continue;
      p.xyz_m = (range * d).cast<float>();
      p.dt_ns = column * 55'000;
      scan.points.push_back(p);
    }
  }
  return scan;
}

/// `vibration_rms` (m/s²) of motors idling added to a level IMU: tones at 21, 42 and 67 Hz,
/// mostly vertical, with 0.02 rad/s of rate per m/s².
ImuSample Shaken(ImuSample s, double vibration_rms) {
  const double t = NsToSec(s.t_ns);
  const double tone = std::sqrt(1.2) * std::sin(2 * M_PI * 21.0 * t) +
                      std::sqrt(0.5) * std::sin(2 * M_PI * 42.0 * t + 0.7) +
                      std::sqrt(0.3) * std::sin(2 * M_PI * 67.0 * t + 1.9);
  s.acc_mps2 += vibration_rms * tone * Vec3(0.45, 0.45, 0.77);
  s.gyro_radps += 0.02 * vibration_rms * tone * Vec3(0.67, 0.67, 0.32);
  return s;
}

/// Stands still 2 s for the static initialization, then `sweeps` corridor sweeps while the
/// accelerometer's bias steps by 0.03 m/s² along the corridor (within the rest limits), the
/// chassis vibrating with `vibration_rms`. The last result.
WindowResult StandInACorridorWithABiasStep(const WindowEstimatorConfig& config,
                                           int sweeps,
                                           double vibration_rms = 0.0) {
  WindowEstimator estimator(config);
  int64_t t = 0;
  for (; t < 2 * kNsPerSec; t += 2'500'000) {
    estimator.AddImu(Shaken(test::LevelImu(t), vibration_rms));
  }
  EXPECT_TRUE(estimator.initialized());
  WindowResult r;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    const int64_t t_end = t + 100 * kNsPerMs;
    for (; t < t_end; t += 2'500'000) {
      estimator.AddImu(Shaken(test::LevelImu(t, 0.03), vibration_rms));
    }
    r = estimator.AddScan(CorridorSweep(t_end - 100 * kNsPerMs));
    EXPECT_EQ(r.odometry.status, OdometryStatus::kTracking) << "sweep " << sweep;
  }
  return r;
}

TEST(WindowEstimator, AtRestTheZeroVelocityFactorHoldsThePose) {
  WindowEstimatorConfig config;
  config.standstill.enabled = true;
  const WindowResult held = StandInACorridorWithABiasStep(config, 50);
  EXPECT_GE(held.standstill_frames, 45u);
  EXPECT_LT(held.odometry.state.T_world_imu.translation().norm(), 0.01);
  EXPECT_LT(held.odometry.state.vel_world.norm(), 0.01);
  // Without it the bias step is integrated along the corridor.
  config.standstill.enabled = false;
  const WindowResult drifted = StandInACorridorWithABiasStep(config, 50);
  EXPECT_EQ(drifted.standstill_frames, 0u);
  EXPECT_GT(drifted.odometry.state.T_world_imu.translation().norm(), 0.05);
  std::cout << "[ standstill ] after 5 s: " << held.odometry.state.T_world_imu.translation().norm()
            << " m held, " << drifted.odometry.state.T_world_imu.translation().norm()
            << " m without\n";
}

/// The same with the motors idling (issue 36): still recognized as rest, the pose still held.
TEST(WindowEstimator, AtRestWithChassisVibrationTheZeroVelocityFactorStillHolds) {
  WindowEstimatorConfig config;
  for (const double rms : {0.5, 2.0}) {
    const WindowResult held = StandInACorridorWithABiasStep(config, 50, rms);
    EXPECT_GE(held.standstill_frames, 45u) << rms;
    // The factor loosens with the measured spread (0.009 m/s at 2 m/s²), so a little more of
    // the bias step gets through than at a quiet rest (0.4 cm); without it: > 5 cm.
    EXPECT_LT(held.odometry.state.T_world_imu.translation().norm(), 0.035) << rms;
    std::cout << "[ standstill ] " << rms << " m/s² RMS: " << held.standstill_frames
              << " frames at rest, " << held.odometry.state.T_world_imu.translation().norm()
              << " m after 5 s\n";
  }
}

}  // namespace
}  // namespace swlio::estimator

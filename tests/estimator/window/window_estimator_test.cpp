// WindowEstimator's contract: initialization, the window's size and its marginalization prior,
// configuration. Its accuracy on simulated drives is tested end to end through swlio-run
// (tests/tools/run_command_test.cpp).

#include "swlio/estimator/window/window_estimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "swlio/core/time.h"
#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"
#include "wall_sweep.h"

namespace swlio::estimator {
namespace {

using test::LevelImu;
using test::WallSweep;

/// 2 s level and still at 400 Hz (the static initialization), then `sweeps` sweeps of a wall at
/// 10 Hz standing still; the last result. Every sweep must be tracked within the window size.
WindowResult StandStill(const WindowEstimatorConfig& config, int sweeps = 12) {
  WindowEstimator estimator(config);
  int64_t t = 0;
  for (; t < 2 * kNsPerSec; t += 2'500'000) estimator.AddImu(LevelImu(t));
  EXPECT_TRUE(estimator.initialized());
  WindowResult r;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    const int64_t t_end = t + 100 * kNsPerMs;
    for (; t < t_end; t += 2'500'000) estimator.AddImu(LevelImu(t));
    r = estimator.AddScan(WallSweep(t_end - 100 * kNsPerMs));
    EXPECT_NE(r.odometry.status, OdometryStatus::kInitializing) << "sweep " << sweep;
    EXPECT_LE(r.window_frames, config.window_size);
  }
  return r;
}

TEST(WindowEstimator, StandingStillTheImuHoldsThePoseAndTheWindowSlides) {
  WindowEstimatorConfig config;
  config.window_size = 4;
  config.estimate_gravity_tilt = false;  // the map frame is gravity-aligned by definition
  const WindowResult r = StandStill(config);
  EXPECT_EQ(r.window_frames, config.window_size);
  // After marginalization the prior spans the oldest kept frame's pose and speed/bias (15).
  EXPECT_EQ(r.prior_rank, 15);
  EXPECT_GT(r.solver_iterations, 0);
  EXPECT_LT(r.odometry.state.T_world_imu.translation().norm(), 1e-3);
  EXPECT_LT(r.odometry.state.vel_world.norm(), 1e-3);
  EXPECT_EQ(r.odometry.times.total_ms, 0.0) << "no clock injected: no timings";
}

// A sweep that starts before the newest frame (out of order) is not used, and says so: a
// consumer must not take its empty state, nor read it as "initializing again".
TEST(WindowEstimator, AnOutOfOrderSweepIsSkippedAndTrackingGoesOn) {
  WindowEstimatorConfig config;
  config.window_size = 4;
  WindowEstimator estimator(config);
  int64_t t = 0;
  for (; t < 2 * kNsPerSec; t += 2'500'000) estimator.AddImu(LevelImu(t));
  ASSERT_TRUE(estimator.initialized());
  for (int sweep = 0; sweep < 3; ++sweep) {
    const int64_t t_end = t + 100 * kNsPerMs;
    for (; t < t_end; t += 2'500'000) estimator.AddImu(LevelImu(t));
    const OdometryStatus s = estimator.AddScan(WallSweep(t_end - 100 * kNsPerMs)).odometry.status;
    ASSERT_TRUE(s == OdometryStatus::kTracking || s == OdometryStatus::kMatchFailed);  // used
  }
  const WindowResult late = estimator.AddScan(WallSweep(t - 150 * kNsPerMs));
  EXPECT_EQ(late.odometry.status, OdometryStatus::kSkipped);
  const int64_t t_end = t + 100 * kNsPerMs;
  for (; t < t_end; t += 2'500'000) estimator.AddImu(LevelImu(t));
  const WindowResult next = estimator.AddScan(WallSweep(t_end - 100 * kNsPerMs));
  EXPECT_TRUE(next.odometry.status == OdometryStatus::kTracking ||
              next.odometry.status == OdometryStatus::kMatchFailed);
  EXPECT_EQ(next.odometry.state.t_ns, t_end - kNsPerMs);  // WallSweep lasts 99 ms
}

TEST(WindowEstimator, WithTheGravityTiltThePriorAlsoSpansIt) {
  WindowEstimatorConfig config;
  config.window_size = 4;
  config.estimate_gravity_tilt = true;
  const WindowResult r = StandStill(config);
  EXPECT_EQ(r.window_frames, config.window_size);
  // The oldest kept frame's pose and speed/bias (15) and the map's tilt against gravity (2).
  EXPECT_EQ(r.prior_rank, 15 + kGravityTiltSize);
  // Level and at rest: nothing tilts the map against gravity, nothing moves.
  EXPECT_LT(r.gravity_tilt_rad.norm(), 1e-4);
  EXPECT_LT(r.odometry.state.T_world_imu.translation().norm(), 1e-3);
  EXPECT_LT(r.odometry.state.vel_world.norm(), 1e-3);
  EXPECT_TRUE(r.covariance.valid);
}

TEST(WindowEstimator, ABiasedGyroAtRestIsEstimatedNotIntegrated) {
  // The static initializer takes b_g from the first second; the window must keep it.
  WindowEstimator estimator(WindowEstimatorConfig{});
  const Eigen::Vector3d bias(0.002, -0.003, 0.004);
  int64_t t = 0;
  auto sample = [&](int64_t t_ns) {
    ImuSample s = LevelImu(t_ns);
    s.gyro_radps = bias;
    return s;
  };
  for (; t < 2 * kNsPerSec; t += 2'500'000) estimator.AddImu(sample(t));
  ASSERT_TRUE(estimator.initialized());
  WindowResult r;
  for (int sweep = 0; sweep < 20; ++sweep) {
    const int64_t t_end = t + 100 * kNsPerMs;
    for (; t < t_end; t += 2'500'000) estimator.AddImu(sample(t));
    r = estimator.AddScan(WallSweep(t_end - 100 * kNsPerMs));
  }
  EXPECT_LT((r.odometry.state.bias_gyro - bias).norm(), 1e-4);
  EXPECT_LT(Eigen::AngleAxisd(r.odometry.state.T_world_imu.linear()).angle(), 1e-3);
}

// The newest state's covariance in the first result is the first frame's prior (the map is still
// empty): after this standing start the diagonal one gives the tilt b_a's σ / g (what the static
// initialization cannot tell from a bias, StaticStartTiltSigma) without correlation; the
// correlated one (init_tilt_follows_bias) ties it to b_a across the up axis (initial_prior.h).
// That is in a map frame gravity-aligned by definition (estimate_gravity_tilt off).
TEST(WindowEstimator, FirstCovarianceIsTheInitialPrior) {
  for (const bool correlated : {false, true}) {
    WindowEstimatorConfig config;
    config.estimate_gravity_tilt = false;
    config.init_tilt_follows_bias = correlated;
    const WindowResult r = StandStill(config, 1);
    ASSERT_TRUE(r.covariance.valid) << "correlated " << correlated;
    const StateCovarianceMatrix& P = r.covariance.P;
    const double tilt_x = std::sqrt(P(kCovRot, kCovRot));
    // Level robot: tilt about world x is matched by b_a along body y (δf = g [u]× δφ + δb_a).
    const double rho = P(kCovRot, kCovBiasAcc + 1) /
                       std::sqrt(P(kCovRot, kCovRot) * P(kCovBiasAcc + 1, kCovBiasAcc + 1));
    EXPECT_NEAR(std::sqrt(P(kCovVel, kCovVel)), config.init_sigma_velocity_mps, 0.01);
    if (correlated) {
      EXPECT_GT(tilt_x, 3e-3) << "b_a σ 0.05 m/s² reads as ~5 mrad of tilt";
      EXPECT_GT(std::abs(rho), 0.9);
    } else {
      EXPECT_NEAR(tilt_x, config.init_sigma_bias_acc_mps2 / 9.80665, 1e-4);
      EXPECT_NEAR(tilt_x, StaticStartTiltSigma(config), 1e-4);
      EXPECT_LT(std::abs(rho), 0.05);
    }
    // Q = I: the attitude against gravity is the map-frame attitude.
    EXPECT_TRUE(r.covariance.rot_gravity.isApprox(P.block<3, 3>(kCovRot, kCovRot), 1e-12));
  }
}

// With the map's tilt estimated, the first frame's tilt is the map's gauge and the ambiguity
// sits in the tilt block: the attitude against gravity has both.
TEST(WindowEstimator, WithTheMapTiltTheAttitudeAgainstGravityCarriesTheStartsAmbiguity) {
  WindowEstimatorConfig config;
  config.estimate_gravity_tilt = true;
  const WindowResult r = StandStill(config, 1);
  ASSERT_TRUE(r.covariance.valid);
  const double map_tilt_x = std::sqrt(r.covariance.P(kCovRot, kCovRot));
  const double gravity_tilt_x = std::sqrt(r.covariance.rot_gravity(0, 0));
  const double ambiguity = config.init_sigma_bias_acc_mps2 / config.odometry.estimator.gravity_mps2;
  EXPECT_NEAR(map_tilt_x, config.init_sigma_rotation_rad, 1e-4);
  EXPECT_NEAR(gravity_tilt_x, std::hypot(config.init_sigma_rotation_rad, ambiguity), 2e-4);
  // Yaw is not tilted by Q.
  EXPECT_NEAR(r.covariance.rot_gravity(2, 2), r.covariance.P(kCovRot + 2, kCovRot + 2), 1e-9);
}

/// The first result's gyro-bias σ per axis after a standing start on a gyro with white noise of
/// `gyro_sigma_radps` per sample (400 Hz), or NaN when it did not initialize.
Eigen::Vector3d FirstGyroBiasSigma(double gyro_sigma_radps,
                                   const WindowEstimatorConfig& config = WindowEstimatorConfig{}) {
  WindowEstimator estimator(config);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, gyro_sigma_radps);
  auto sample = [&](int64_t t_ns) {
    ImuSample s = LevelImu(t_ns);
    s.gyro_radps = Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    return s;
  };
  int64_t t = 0;
  for (; !estimator.initialized() && t < 3 * kNsPerSec; t += 2'500'000) {
    estimator.AddImu(sample(t));
  }
  if (!estimator.initialized()) return Eigen::Vector3d::Constant(std::nan(""));
  const int64_t t_end = t + 100 * kNsPerMs;
  for (; t < t_end; t += 2'500'000) estimator.AddImu(sample(t));
  const WindowResult r = estimator.AddScan(WallSweep(t_end - 100 * kNsPerMs));
  if (!r.covariance.valid) return Eigen::Vector3d::Constant(std::nan(""));
  return r.covariance.P.block<3, 3>(kCovBiasGyro, kCovBiasGyro).diagonal().cwiseSqrt();
}

// After a standing start the gyro bias is known to the still window's standard error, σ_ω/√N
// (400 samples in the default 1 s), not to the configured 0.005 rad/s: with that loose prior the
// LiDAR's yaw jitter moved the bias while the robot stood
// (docs/notes/2026-11-25-tightly-coupled-yaw-gyro-bias.md, "The gyro bias after a standing
// start"). A noise-free gyro gets the datasheet's density/√T (the still window is 1–1.5 s), or
// the 1e-5 rad/s floor under a density too small for that.
TEST(WindowEstimator, AfterAStandingStartTheGyroBiasIsKnownToTheStillWindowsStandardError) {
  const double sigma_radps = 3.5e-3;  // the MTi-G-710 at 400 Hz: 0.01 °/s/√Hz · √400
  const Eigen::Vector3d noisy = FirstGyroBiasSigma(sigma_radps);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(noisy[axis], sigma_radps / std::sqrt(400.0), 2e-5) << "axis " << axis;
  }
  WindowEstimatorConfig config;
  const double density = config.odometry.estimator.imu_noise.gyro_noise_density_radps_per_sqrthz;
  const Eigen::Vector3d noise_free = FirstGyroBiasSigma(0.0, config);
  EXPECT_LE(noise_free.maxCoeff(), density * 1.001);
  EXPECT_GE(noise_free.minCoeff(), density / std::sqrt(1.5));
  config.odometry.estimator.imu_noise.gyro_noise_density_radps_per_sqrthz = 1e-6;
  const Eigen::Vector3d floored = FirstGyroBiasSigma(0.0, config);
  EXPECT_NEAR(floored.maxCoeff(), 1e-5, 1e-6);
  EXPECT_NEAR(floored.minCoeff(), 1e-5, 1e-6);
}

// The window's own edge settings, not odometry.front_end's, decide its sweeps' edges: a wall has
// none above the default smoothness threshold, and some above a tiny one.
TEST(WindowEstimator, ItsEdgeSettingsReachTheFrontEnd) {
  WindowEstimatorConfig config;
  config.window_size = 4;
  config.odometry.front_end.features.edge_threshold_m2 = 1e-6;  // not the window's: ignored
  EXPECT_EQ(StandStill(config).odometry.edges, 0u);
  config.edge_threshold_m2 = 1e-6;
  EXPECT_GT(StandStill(config).odometry.edges, 0u);
  config.max_edges_per_sector = 2;
  const WindowEstimatorConfig applied = WithWindowFeatures(config);
  EXPECT_EQ(applied.odometry.front_end.features.edge_threshold_m2, 1e-6);
  EXPECT_EQ(applied.odometry.front_end.features.max_edges_per_sector, 2);
}

TEST(WindowEstimatorConfig, ValidateNamesTheBadKeys) {
  WindowEstimatorConfig config;
  EXPECT_TRUE(config.Validate().empty());
  config.window_size = 1;
  config.lidar_sigma_m = 0.0;
  config.odometry.min_inliers = 1;
  const ConfigIssues issues = config.Validate();
  ASSERT_EQ(issues.size(), 3u);
  EXPECT_EQ(issues[0].key, "odometry.min_inliers");
  EXPECT_EQ(issues[1].key, "window_size");
  EXPECT_EQ(issues[2].key, "lidar_sigma_m");
}

}  // namespace
}  // namespace swlio::estimator

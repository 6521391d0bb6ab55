// LidarOdometry's contract around initialization and configuration; its accuracy on simulated
// drives is tested end to end through swlio-run (tests/tools/run_command_test.cpp).

#include "swlio/estimator/registration/lidar_odometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "swlio/core/time.h"
#include "wall_sweep.h"

namespace swlio::estimator {
namespace {

using test::LevelImu;
using test::WallSweep;

TEST(LidarOdometry, SweepsBeforeAStandingStartAreSkipped) {
  LidarOdometry odometry(LidarOdometryConfig{});
  // Rocking back and forth (±0.5 m/s² at 0.5 Hz) for 3 s: never still long enough to
  // initialize. (A shake at 200 Hz would be chassis vibration, which is rest: imu_stillness.h.)
  for (int64_t t = 0; t < 3 * kNsPerSec; t += 2'500'000) {
    odometry.AddImu(LevelImu(t, 0.5 * std::sin(M_PI * NsToSec(t))));
    if (t % (100 * kNsPerMs) == 0 && t > 0) {
      EXPECT_EQ(odometry.AddScan(WallSweep(t - 100 * kNsPerMs)).status,
                OdometryStatus::kInitializing);
    }
  }
  EXPECT_FALSE(odometry.initialized());
  // Standing still: initialized, and the next sweep is used (the first one builds the map).
  int64_t t = 3 * kNsPerSec;
  for (; t < 6 * kNsPerSec; t += 2'500'000) odometry.AddImu(LevelImu(t, 0.0));
  ASSERT_TRUE(odometry.initialized());
  for (int64_t u = t; u < t + 200 * kNsPerMs; u += 2'500'000) odometry.AddImu(LevelImu(u, 0.0));
  const OdometryResult r = odometry.AddScan(WallSweep(t));
  EXPECT_EQ(r.status, OdometryStatus::kTracking);
  EXPECT_EQ(r.points_in, 100u);
  EXPECT_EQ(r.state.t_ns, t + 99 * kNsPerMs);
  // Standing: no motion but the IMU's own dead reckoning since the initialization (2 s): the
  // rocking's last 0.1 s leaks 1e-3 m/s² into the still window's tapered mean, a 0.007° tilt,
  // 2.4 mm after 2 s.
  EXPECT_LT(r.state.T_world_imu.translation().norm(), 5e-3) << "standing: no motion";
  EXPECT_EQ(r.times.total_ms, 0.0) << "no clock injected: no timings";
  // A sweep that starts before the state it would follow is reported, not used.
  EXPECT_EQ(odometry.AddScan(WallSweep(t + 50 * kNsPerMs)).status, OdometryStatus::kSkipped);
}

TEST(LidarOdometry, StageTimesComeFromTheInjectedClock) {
  static int64_t fake_ns = 0;
  const NowNsFn clock = [] { return fake_ns += 1'000'000; };  // +1 ms per reading
  LidarOdometry odometry(LidarOdometryConfig{}, clock);
  int64_t t = 0;
  for (; t < 3 * kNsPerSec; t += 2'500'000) odometry.AddImu(LevelImu(t, 0.0));
  ASSERT_TRUE(odometry.initialized());
  for (int64_t u = t; u < t + 200 * kNsPerMs; u += 2'500'000) odometry.AddImu(LevelImu(u, 0.0));
  const OdometryResult r = odometry.AddScan(WallSweep(t));
  EXPECT_DOUBLE_EQ(r.times.frontend_ms, 1.0);
  EXPECT_DOUBLE_EQ(r.times.match_ms, 0.0) << "first sweep: nothing to match against";
  EXPECT_DOUBLE_EQ(r.times.total_ms, 2.0);
}

TEST(LidarOdometryConfig, ValidateNamesTheBadKeys) {
  LidarOdometryConfig config;
  EXPECT_TRUE(config.Validate().empty());
  config.min_inliers = 1;
  config.matcher.neighbors = 1;
  config.plane_map.voxel_m = 0.0;
  const ConfigIssues issues = config.Validate();
  ASSERT_EQ(issues.size(), 3u);
  EXPECT_EQ(issues[0].key, "matcher.neighbors");
  EXPECT_EQ(issues[1].key, "plane_map.voxel_m");
  EXPECT_EQ(issues[2].key, "min_inliers");
}

// The configuration file's estimator.plane_voxel_m, edge_voxel_m and local_map_radius_m reach
// the front end and the maps (they were read and then ignored: the defaults happened to agree).
TEST(LidarOdometryConfig, MadeFromTheEstimatorSection) {
  EstimatorConfig estimator;
  estimator.plane_voxel_m = 0.7;
  estimator.edge_voxel_m = 0.15;
  estimator.local_map_radius_m = 120.0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << 0.1, -0.2, 0.3;
  const LidarOdometryConfig c = MakeOdometryConfig(estimator, T);
  EXPECT_EQ(c.front_end.plane_voxel_m, 0.7);
  EXPECT_EQ(c.front_end.edge_voxel_m, 0.15);
  EXPECT_EQ(c.plane_map.radius_m, 120.0);
  EXPECT_EQ(c.edge_map.radius_m, 120.0);
  EXPECT_TRUE(c.T_imu_lidar.isApprox(T));
  EXPECT_EQ(c.estimator.local_map_radius_m, 120.0);
  // The defaults of the section give the defaults of the odometry.
  const LidarOdometryConfig d = MakeOdometryConfig(EstimatorConfig{}, T);
  const LidarOdometryConfig plain;
  EXPECT_EQ(d.front_end.plane_voxel_m, plain.front_end.plane_voxel_m);
  EXPECT_EQ(d.front_end.edge_voxel_m, plain.front_end.edge_voxel_m);
  EXPECT_EQ(d.plane_map.radius_m, plain.plane_map.radius_m);
  EXPECT_EQ(d.edge_map.radius_m, plain.edge_map.radius_m);
}

}  // namespace
}  // namespace swlio::estimator

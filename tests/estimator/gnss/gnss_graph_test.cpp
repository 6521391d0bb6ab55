// GNSS in the pose graph (gnss_associator.h, loop_closure.h with `gnss`): a drifting odometry
// around a rectangle with noisy fixes at 4 Hz comes out georeferenced and without the drift;
// a multipath jump with an optimistic accuracy is switched off; the gates count what they drop.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "swlio/core/geodetic.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/gnss/gnss_associator.h"
#include "swlio/estimator/loop/loop_closure.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

const Geodetic kOrigin{31.0, 121.0, 10.0};
const Vec3 kAntennaImu(-0.2, 0.0, 0.5);

/// True IMU pose in ENU at `t_s` (1 m/s around a 100 m × 60 m rectangle, starting away from the
/// ENU origin and heading north-east, so the alignment has yaw and translation to find).
Eigen::Isometry3d TruthEnu(double t_s) {
  const double s = std::fmod(t_s, 320.0);
  Vec3 p;
  double heading;
  if (s < 100.0) {
    p = {s, 0.0, 0.0}, heading = 0.0;
  } else if (s < 160.0) {
    p = {100.0, s - 100.0, 0.0}, heading = M_PI / 2;
  } else if (s < 260.0) {
    p = {260.0 - s, 60.0, 0.0}, heading = M_PI;
  } else {
    p = {0.0, 320.0 - s, 0.0}, heading = -M_PI / 2;
  }
  Eigen::Isometry3d T_enu_track = Eigen::Isometry3d::Identity();
  T_enu_track.linear() = Eigen::AngleAxisd(0.6, Vec3::UnitZ()).toRotationMatrix();
  T_enu_track.translation() = Vec3(-40.0, 25.0, 3.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(heading, Vec3::UnitZ()).toRotationMatrix();
  T.translation() = p;
  return T_enu_track * T;
}

struct GnssRun {
  double rms_corrected_m = 0.0;  ///< georeferenced nodes against the truth
  double rms_odometry_m = 0.0;   ///< odometry nodes, best 4-DoF fit to the truth
  LoopClosureStats stats;
};

/// `jump_m` east on the fixes between 150 s and 160 s (reported accuracy unchanged); σ inflated
/// for `correlation_time_s` (the fix errors here are white: 0 weighs them as they are).
GnssRun Simulate(double jump_m, double correlation_time_s = 0.0) {
  LoopClosureConfig c;
  c.enabled = false;  // GNSS only
  c.gnss.enabled = true;
  c.gnss.origin_lat_deg = kOrigin.lat_deg;
  c.gnss.origin_lon_deg = kOrigin.lon_deg;
  c.gnss.origin_height_m = kOrigin.height_m;
  c.gnss.antenna_imu_m = kAntennaImu;
  c.gnss.correlation_time_s = correlation_time_s;
  LoopClosure loop(c);
  const LocalEnu enu(kOrigin);
  std::mt19937 rng(7);
  std::normal_distribution<double> n01(0.0, 1.0);

  // Odometry: the true increments with a 1 % scale error and 1e-4 rad of yaw per step.
  const double dt = 0.1;
  Eigen::Isometry3d T_odom = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_prev_true = TruthEnu(0.0);
  double next_fix_s = 0.0;
  for (double t = 0.0; t < 400.0; t += dt) {
    const auto t_ns = static_cast<int64_t>(std::llround(t * 1e9));
    const Eigen::Isometry3d T_true = TruthEnu(t);
    Eigen::Isometry3d d = T_prev_true.inverse() * T_true;
    d.translation() *= 1.01;
    d.linear() = d.linear() * Eigen::AngleAxisd(1e-4, Vec3::UnitZ()).toRotationMatrix();
    T_odom = T_odom * d;
    T_prev_true = T_true;
    while (next_fix_s <= t) {
      Vec3 antenna = TruthEnu(next_fix_s) * kAntennaImu;
      antenna += Vec3(0.5 * n01(rng), 0.5 * n01(rng), 1.0 * n01(rng));
      if (next_fix_s >= 150.0 && next_fix_s < 160.0) antenna.x() += jump_m;
      const Geodetic g = enu.ToGeodetic(antenna);
      GnssFix fix;
      fix.t_ns = static_cast<int64_t>(std::llround(next_fix_s * 1e9));
      fix.lat_deg = g.lat_deg, fix.lon_deg = g.lon_deg, fix.height_m = g.height_m;
      fix.h_acc_m = 0.5, fix.v_acc_m = 1.0, fix.fix_type = 3, fix.num_sv = 12;
      loop.AddGnss(fix);
      next_fix_s += 0.25;
    }
    loop.AddKeyframe(KeyframeCloud{t_ns, T_odom, Eigen::Isometry3d::Identity(), {}, {}, nullptr});
  }
  GnssRun r;
  r.stats = loop.stats();
  const auto T_enu_map = loop.T_enu_map();
  if (!T_enu_map) return r;
  std::vector<Vec3> odom, truth;
  double sum = 0.0;
  for (size_t i = 0; i < loop.nodes(); ++i) {
    const double t_s = static_cast<double>(loop.node(i).t_ns) * 1e-9;
    const Vec3 p_true = TruthEnu(t_s).translation();
    sum += ((*T_enu_map * loop.T_map_imu(i)).translation() - p_true).squaredNorm();
    odom.push_back(loop.node(i).T_world_imu.translation());
    truth.push_back(p_true);
  }
  r.rms_corrected_m = std::sqrt(sum / static_cast<double>(loop.nodes()));
  const Eigen::Isometry3d fit = FitEnuAlignment(odom, truth);
  sum = 0.0;
  for (size_t i = 0; i < odom.size(); ++i) sum += (fit * odom[i] - truth[i]).squaredNorm();
  r.rms_odometry_m = std::sqrt(sum / static_cast<double>(odom.size()));
  return r;
}

TEST(GnssGraph, RemovesDriftAndGeoreferences) {
  const GnssRun r = Simulate(0.0);
  ASSERT_TRUE(r.stats.gnss_aligned);
  std::printf("[ gnss ] nodes %zu, edges %zu, odometry RMS %.2f m, corrected RMS %.3f m\n",
              r.stats.nodes, r.stats.gnss_edges, r.rms_odometry_m, r.rms_corrected_m);
  EXPECT_GT(r.rms_odometry_m, 2.0);  // the drift is real
  EXPECT_LT(r.rms_corrected_m, 0.5);
  // 1 fix per second taken out of 4 (min_interval_s), the rest counted.
  EXPECT_GT(r.stats.gnss.rate_limited, 2 * r.stats.gnss.observations);
  EXPECT_GT(r.stats.gnss_edges, 300u);
}

TEST(GnssGraph, GatesAMultipathJump) {
  // With the default correlation inflation (σ × √30; this odometry drifts hard, so the graph
  // follows the fixes more loosely than with white weights): the 20 m jump of ten fixes (one
  // per second) is refused by the innovation gate, and the result is as without the jump.
  const GnssRun clean = Simulate(0.0, 30.0);
  const GnssRun r = Simulate(20.0, 30.0);
  ASSERT_TRUE(r.stats.gnss_aligned);
  std::printf("[ gnss ] jump: gated %zu, switched off %zu, corrected RMS %.3f m (%.3f without)\n",
              r.stats.gnss_gated, r.stats.gnss_switched_off, r.rms_corrected_m,
              clean.rms_corrected_m);
  EXPECT_GE(r.stats.gnss_gated + r.stats.gnss_switched_off, 8u);
  EXPECT_LE(r.stats.gnss_gated + r.stats.gnss_switched_off, 15u);
  EXPECT_LE(clean.stats.gnss_gated + clean.stats.gnss_switched_off, 3u);
  EXPECT_LT(clean.rms_corrected_m, 1.0);
  EXPECT_LT(r.rms_corrected_m, 1.1 * clean.rms_corrected_m);
}

TEST(GnssAssociator, GatesAndPlacesFixes) {
  GnssConfig c;
  c.enabled = true;
  c.antenna_imu_m = kAntennaImu;
  c.correlation_time_s = 4.0;  // σ × √(4 s / 1 s) = × 2
  GnssAssociator a(c);         // origin: the first accepted fix
  const LocalEnu enu(kOrigin);
  auto fix_at = [&](double t_s, const Vec3& enu_m, uint8_t type, double h_acc) {
    const Geodetic g = enu.ToGeodetic(enu_m);
    return GnssFix{static_cast<int64_t>(t_s * 1e9),
                   g.lat_deg,
                   g.lon_deg,
                   g.height_m,
                   h_acc,
                   2.0 * h_acc,
                   type,
                   10};
  };
  a.AddFix(fix_at(0.5, {0, 0, 0}, 2, 1.0));      // 2-D fix: below min_fix_type
  a.AddFix(fix_at(0.6, {0, 0, 0}, 3, 50.0));     // accuracy too poor
  a.AddFix(fix_at(1.0, {10, 0, 0}, 3, 1.0));     // taken, and the origin
  a.AddFix(fix_at(1.5, {11, 0, 0}, 3, 1.0));     // within min_interval_s
  a.AddFix(fix_at(2.05, {12, 0.5, 0}, 3, 1.0));  // taken
  GnssFix nan_fix = fix_at(3.5, {0, 0, 0}, 3, 1.0);
  nan_fix.lat_deg = NAN;
  a.AddFix(nan_fix);
  EXPECT_EQ(a.stats().bad_quality, 3u);
  EXPECT_EQ(a.stats().rate_limited, 1u);
  ASSERT_TRUE(a.origin().has_value());

  // Odometry at 0.9 s (rotated 90°) and 2.1 s; nodes at 0.9 s only.
  Eigen::Isometry3d T0 = Eigen::Isometry3d::Identity();
  T0.linear() = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
  Eigen::Isometry3d T1 = T0;
  T1.translation() = Vec3(0.0, 1.2, 0.0);  // 1.2 m along its own x (world y) in 1.2 s
  std::vector<KeyframeCloud> nodes = {
      {900'000'000, T0, Eigen::Isometry3d::Identity(), {}, {}, nullptr}};
  a.AddOdometry(900'000'000, T0);
  EXPECT_TRUE(a.Take(nodes).empty());  // no odometry past the fixes yet
  a.AddOdometry(2'100'000'000, T1);
  const std::vector<GnssObservation> obs = a.Take(nodes);
  ASSERT_EQ(obs.size(), 2u);
  EXPECT_EQ(obs[0].node, 0u);
  // At 1.0 s the IMU is 0.1 m ahead of the node (its x): the antenna sits there plus the lever.
  EXPECT_LT((obs[0].antenna_imu_m - (kAntennaImu + Vec3(0.1, 0, 0))).norm(), 1e-9);
  EXPECT_LT(obs[0].fix_enu_m.norm(), 1e-6);  // the origin itself
  // 2 m from the first fix, in the tangent plane at that fix (not at kOrigin, 10 m west: the
  // two planes differ by ~d²/2R ≈ 1e-5 m here).
  EXPECT_LT((obs[1].fix_enu_m - Vec3(2.0, 0.5, 0.0)).norm(), 1e-4);
  EXPECT_NEAR(obs[1].sigma_h_m, 2.0, 1e-12);
  EXPECT_NEAR(obs[1].sigma_v_m, 4.0, 1e-12);
  EXPECT_EQ(a.stats().observations, 2u);
}

}  // namespace
}  // namespace swlio::estimator

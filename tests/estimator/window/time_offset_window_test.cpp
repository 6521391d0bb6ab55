// The window with an unknown LiDAR–IMU time offset (time_offset_estimator.h, hooked into
// WindowEstimator): 40 s of `aggressive` seed 42 with the IMU measuring the motion 8 ms before
// its stamps (and, in a second window fed the same sweeps, 6 ms after), the sweeps straight from
// the simulator's truth (perfectly de-skewed, so that the offset is exactly the simulated one: no
// clock model in between). The estimate must be within 0.5 ms after 30 s of motion, applied,
// and reported in every result. On `aggressive` seed 1 the window's factors, moved to the
// estimate as it comes, must keep the drive's first turn.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <tuple>

#include "sensors/labelled_scan.h"
#include "sim_imu_util.h"
#include "swlio/core/time.h"
#include "swlio/estimator/window/window_estimator.h"

namespace swlio::estimator {
namespace {

/// The sweep with every point at its end: the simulator already moved the points into the
/// LiDAR frame at the last firing, so the window's de-skew must leave them there.
Scan AtItsEnd(Scan scan) {
  const int64_t span_ns = scan.t_end_ns - scan.t_start_ns;
  for (LidarPoint& p : scan.points) p.dt_ns = span_ns;
  return scan;
}

struct OffsetWindow {
  OffsetWindow(const sim::SimSetup& setup,
               double offset_s,
               double window_prior_sigma_s = 0.0,
               bool follows_estimate = true) {
    sim::ImuSimConfig imu_config = setup.imu;
    imu_config.time_offset_s = offset_s;
    imu = test::ToImuSamples(sim::SimulateImu(*setup.trajectory, imu_config, 42));
    WindowEstimatorConfig config;
    config.odometry.T_imu_lidar = setup.lidar.T_imu_lidar;
    config.time_offset.window_prior_sigma_s = window_prior_sigma_s;
    config.time_offset.window_follows_estimate = follows_estimate;
    window = std::make_unique<WindowEstimator>(config);
  }
  /// The samples up to `t_ns` (stamps), then the sweep.
  WindowResult Add(const Scan& scan) {
    for (; next < imu.size() && imu[next].t_ns <= scan.t_end_ns; ++next) window->AddImu(imu[next]);
    return window->AddScan(scan);
  }
  std::vector<ImuSample> imu;
  size_t next = 0;
  std::unique_ptr<WindowEstimator> window;
};

TEST(TimeOffsetWindow, AnUnknownOffsetIsFoundAndAppliedOnAnAggressiveDrive) {
  auto setup = sim::MakeSimSetup("aggressive", 42, 40.0);
  ASSERT_TRUE(setup.has_value());
  OffsetWindow late(*setup, 0.008), early(*setup, -0.006);
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  WindowResult r_late, r_early;
  size_t diverged = 0, tracked = 0;
  while (source.Next(&ls)) {
    const Scan scan = AtItsEnd(ls.scan);
    r_late = late.Add(scan);
    r_early = early.Add(scan);
    for (const WindowResult* r : {&r_late, &r_early}) {
      diverged += r->diverged != DivergenceReason::kNone ? 1 : 0;
      tracked += r->odometry.status == OdometryStatus::kTracking ? 1 : 0;
    }
  }
  for (const auto& [name, r, truth] :
       {std::tuple{"late", &r_late, 0.008}, std::tuple{"early", &r_early, -0.006}}) {
    const TimeOffsetStatus& s = r->time_offset;
    std::cout << name << ": truth " << truth * 1e3 << " ms, applied " << s.offset_s * 1e3
              << " ms, estimate " << s.estimate_s * 1e3 << " ± " << s.sigma_s * 1e3 << " ms, rows "
              << s.rows << ", updates " << s.updates << "\n";
    EXPECT_TRUE(s.enabled);
    EXPECT_NEAR(s.estimate_s, truth, 5e-4) << name;
    EXPECT_NEAR(s.offset_s, truth, 5e-4) << name;
    EXPECT_GT(s.updates, 0u) << name;
    EXPECT_FALSE(s.window_offset_s.has_value()) << name;  // not asked for
  }
  EXPECT_EQ(diverged, 0u);
  EXPECT_GT(tracked, 2u * 330u);  // 38 s after the standing start, both windows
}

// The window's own offset parameter (window_prior_sigma_s): free from the estimator's first
// estimate on, it must hold the truth as well as the estimator beside it, and be reported.
TEST(TimeOffsetWindow, TheWindowsOwnOffsetHoldsTheTruth) {
  auto setup = sim::MakeSimSetup("aggressive", 42, 40.0);
  ASSERT_TRUE(setup.has_value());
  const double truth_s = -0.008;
  OffsetWindow w(*setup, truth_s, 0.005);
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  WindowResult r;
  size_t diverged = 0, reported = 0;
  double worst_after_30s = 0.0;
  while (source.Next(&ls)) {
    r = w.Add(AtItsEnd(ls.scan));
    diverged += r.diverged != DivergenceReason::kNone ? 1 : 0;
    if (!r.time_offset.window_offset_s) continue;
    ++reported;
    if (NsToSec(ls.scan.t_end_ns) > 31.0) {
      worst_after_30s =
          std::max(worst_after_30s, std::abs(*r.time_offset.window_offset_s - truth_s));
    }
  }
  std::cout << "window offset at the end " << r.time_offset.window_offset_s.value_or(0.0) * 1e3
            << " ms (truth " << truth_s * 1e3 << "), worst after 30 s " << worst_after_30s * 1e3
            << " ms, reported in " << reported << " results\n";
  EXPECT_EQ(diverged, 0u);
  EXPECT_GT(reported, 200u);  // from the first estimate (~9 s) on
  ASSERT_TRUE(r.time_offset.window_offset_s.has_value());
  EXPECT_GT(worst_after_30s, 0.0);
  EXPECT_LT(worst_after_30s, 5e-4);
  EXPECT_NEAR(r.time_offset.offset_s, truth_s, 5e-4);
}

/// The largest rotation error of a window's LiDAR pose over [from_s, to_s], relative to its
/// pose at `reference_s` (the estimate's rotation since then against the truth's), and where.
struct RotationDrift {
  RotationDrift(double reference_s, double from_s, double to_s)
      : reference_s(reference_s), from_s(from_s), to_s(to_s) {}
  void Add(const WindowResult& r, const sim::LabelledScan& ls) {
    const double t_s = NsToSec(ls.scan.t_end_ns);
    if (r.odometry.status != OdometryStatus::kTracking || t_s < reference_s || t_s > to_s) return;
    const Eigen::Matrix3d R_est = r.odometry.match.T_world_lidar.linear();
    const Eigen::Matrix3d R_true = ls.T_world_lidar_end.linear();
    if (!started) {
      R_est0 = R_est;
      R_true0 = R_true;
      started = true;
      return;
    }
    const Eigen::Matrix3d error =
        (R_true0.transpose() * R_true).transpose() * (R_est0.transpose() * R_est);
    const double angle_rad = Eigen::AngleAxisd(error).angle();
    if (t_s >= from_s && angle_rad > worst_rad) {
      worst_rad = angle_rad;
      worst_t_s = t_s;
    }
  }
  double reference_s, from_s, to_s;
  bool started = false;
  Eigen::Matrix3d R_est0, R_true0;
  double worst_rad = 0.0, worst_t_s = 0.0;
};

// window_follows_estimate: `aggressive` seed 1 drives straight until its first sharp turn
// (8.5–10.2 s); the IMU measures the motion 10 ms after its stamps. The estimate passes the gate
// a few sweeps into the turn, while the factors of the turn's first sweeps, made at the offset
// applied then (0), are still in the window. Moved to the estimate, they no longer
// bend the window's attitude: from the first gated estimate (9.0 s) to 12 s,
// its rotation since 8 s must stay within 0.1° of the truth (measured 0.065°; the offset known:
// 0.04–0.06°), where factors left at the applied offset lose 0.2°. (The sweep before, at
// 8.9 s, is off by 0.09° in both: nothing knows the offset yet.)
TEST(TimeOffsetWindow, TheFactorsFollowingTheEstimateKeepTheFirstTurn) {
  auto setup = sim::MakeSimSetup("aggressive", 1, 13.0);
  ASSERT_TRUE(setup.has_value());
  const double truth_s = -0.010;
  OffsetWindow follows(*setup, truth_s), stays(*setup, truth_s, 0.0, false);
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  RotationDrift d_follows(8.0, 9.0, 12.0), d_stays(8.0, 9.0, 12.0);
  WindowResult r;
  while (source.Next(&ls)) {
    const Scan scan = AtItsEnd(ls.scan);
    r = follows.Add(scan);
    d_follows.Add(r, ls);
    d_stays.Add(stays.Add(scan), ls);
  }
  const double deg = 180.0 / M_PI;
  std::cout << "rotation error across the first turn: factors following the estimate "
            << d_follows.worst_rad * deg << "° (at " << d_follows.worst_t_s
            << " s), left at the applied offset " << d_stays.worst_rad * deg << "° (at "
            << d_stays.worst_t_s << " s); offset applied at the end "
            << r.time_offset.offset_s * 1e3 << " ms\n";
  ASSERT_TRUE(d_follows.started && d_stays.started);
  EXPECT_GT(r.time_offset.updates, 0u);  // the offset was found in the turn
  EXPECT_LT(d_follows.worst_rad, 0.1 / deg);
  EXPECT_LT(d_follows.worst_rad, 0.5 * d_stays.worst_rad);
}

}  // namespace
}  // namespace swlio::estimator

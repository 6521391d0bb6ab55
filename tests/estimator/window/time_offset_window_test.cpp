// The window with an unknown LiDAR–IMU time offset (time_offset_estimator.h, hooked into
// WindowEstimator): 40 s of `aggressive` seed 42 with the IMU measuring the motion 8 ms before
// its stamps (and, in a second window fed the same sweeps, 6 ms after), the sweeps straight from
// the simulator's truth (perfectly de-skewed, so that the offset is exactly the simulated one: no
// clock model in between). The estimate must be within 0.5 ms after 30 s of motion, applied,
// and reported in every result.

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
  OffsetWindow(const sim::SimSetup& setup, double offset_s, double window_prior_sigma_s = 0.0) {
    sim::ImuSimConfig imu_config = setup.imu;
    imu_config.time_offset_s = offset_s;
    imu = test::ToImuSamples(sim::SimulateImu(*setup.trajectory, imu_config, 42));
    WindowEstimatorConfig config;
    config.odometry.T_imu_lidar = setup.lidar.T_imu_lidar;
    config.time_offset.window_prior_sigma_s = window_prior_sigma_s;
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

}  // namespace
}  // namespace swlio::estimator

// Issue 34's compatibility proof without ROS: a Fast DDS reader (ROS 2's default middleware,
// swlio-fastdds-echo --tf-check in its own process) plays a ROS 2 node with a tf2 listener on a
// live simulated drive with loop closure on. At every pose's stamp it composes map → odom (the
// latest at or before) · odom → base_link (at the stamp), once /tf_static has placed the sensors
// under base_link, and must get the published base_link pose; every stamp it takes is within
// 150 ms of its own CLOCK_REALTIME (a sanity bound: on the reader's clock); odom → base_link moves
// between two poses no more than the robot does in one IMU period; map → odom takes the loop
// corrections (it ends equal to the correction the loop-closure thread reports). DDS domain 161.
//
// The drive: `short` (60 s, 1.2 m/s along the south road, a left turn onto the east road) with
// loop closure's min_separation_s at 6 s instead of 30 s: a node counts as a revisit of the road
// driven 6 s (7 m) before, within search_radius_m (10 m). Each accepted loop is a real
// correction (15–32 mm measured) through the pose graph, CorrectionSlew and map → odom. With
// the default 30 s no built-in scenario closes a loop in under about 180 s (`degenerate`), three
// times the test's budget; at 10 s the corner of `short` gave one attempt, rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../../ipc/child_process.h"
#include "line_collector.h"
#include "live_drive.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

#ifdef SWLIO_HAVE_FASTDDS_ECHO
using ipc::test_util::ChildProcess;
using test::Line;
using test::LineCollector;

constexpr uint32_t kDomain = 161;

/// The fastest the base frame moves on the route (its origin's speed, m/s, and the body's
/// rotation rate, rad/s): the IMU's velocity plus ω × the lever arm to the base.
std::pair<double, double> MaxBaseRates(const sim::SimSetup& setup,
                                       const Eigen::Isometry3d& T_imu_base,
                                       double duration_s) {
  double v_max = 0.0, w_max = 0.0;
  for (double t = 0.0; t <= duration_s; t += 0.005) {
    const auto k = setup.trajectory->At(t);
    const Eigen::Vector3d v_base =
        k.v_world + k.R_world_body * k.omega_body.cross(T_imu_base.translation());
    v_max = std::max(v_max, v_base.norm());
    w_max = std::max(w_max, k.omega_body.norm());
  }
  return {v_max, w_max};
}

Eigen::Isometry3d StaticOf(const Line& l) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(l.Get("qw"), l.Get("qx"), l.Get("qy"), l.Get("qz"))
                   .normalized()
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(l.Get("x"), l.Get("y"), l.Get("z"));
  return T;
}

double AngleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

/// What the reader's lines show (the ages as seen where the daemon's own stamps allow, below).
struct Figures {
  size_t poses = 0, matched = 0, long_steps = 0, daemon_late = 0;
  double max_pos_m = 0.0, max_rot_deg = 0.0, max_step_m = 0.0, max_step_deg = 0.0;
  double settling_step_m = 0.0, max_age_ms = 0.0, max_daemon_age_ms = 0.0;
  std::map<std::string, size_t> unmatched;
  size_t map_odom = 0, changes = 0;
  Line last_map_odom;
  int64_t first_stamp_ns = 0;  ///< of the first composed pose
};

// The age of each stamp at the daemon's own (in-process) subscriber, taken microseconds after
// the write: how late the daemon published it. A pose the daemon itself wrote over 40 ms after
// its stamp (its threads short of CPU on a loaded 2-core machine) cannot reach any reader within
// 50 ms; such poses are counted and shown, and must stay rare (a run beside other builds, load
// 4–6: 1.2 % of the poses, the worst 0.8 s late; quieter runs: none).
class AgeCheck {
 public:
  explicit AgeCheck(const test::LiveDriveResult& r) {
    for (const auto& p : r.poses)
      daemon_age_ms_[p.msg.t_ns] = static_cast<double>(p.receive_realtime_ns - p.msg.t_ns) * 1e-6;
  }
  /// Adds the reader's age of `stamp_ns`; false when the daemon wrote it late (not counted).
  bool Add(int64_t stamp_ns, double age_ms, Figures* f) const {
    constexpr double kDaemonLateMs = 40.0;
    const auto it = daemon_age_ms_.find(stamp_ns);
    const double daemon_ms = it == daemon_age_ms_.end() ? 0.0 : it->second;
    f->max_daemon_age_ms = std::max(f->max_daemon_age_ms, daemon_ms);
    if (daemon_ms > kDaemonLateMs) return false;
    f->max_age_ms = std::max(f->max_age_ms, std::abs(age_ms));
    return true;
  }

 private:
  std::map<int64_t, double> daemon_age_ms_;
};

void AddPose(const Line& l, const AgeCheck& ages, double imu_period_s, Figures* f) {
  ++f->poses;
  const int64_t stamp_ns = l.Int("stamp_ns");
  f->daemon_late += ages.Add(stamp_ns, l.Get("pose_age_ns") * 1e-6, f) ? 0 : 1;
  if (l.Int("matched") != 1) {
    ++f->unmatched[l.values.at("reason")];
    return;
  }
  ++f->matched;
  f->max_pos_m = std::max(f->max_pos_m, l.Get("pos_err_m"));
  f->max_rot_deg = std::max(f->max_rot_deg, l.Get("rot_err_deg"));
  ages.Add(stamp_ns, l.Get("tf_age_ns") * 1e-6, f);
  const double dt_s = l.Get("odom_step_dt_ns") * 1e-9;
  if (dt_s <= 0.0) {  // the first
    f->first_stamp_ns = stamp_ns;
    return;
  }
  // A pose per IMU sample; a late serial read gives one pose for its samples (several
  // periods): the bound is per period.
  const double periods = std::max(1.0, std::round(dt_s / imu_period_s));
  f->long_steps += periods > 1.0 ? 1 : 0;
  if (stamp_ns - f->first_stamp_ns < 5'000'000'000) {  // shown apart: the start
    f->settling_step_m = std::max(f->settling_step_m, l.Get("odom_step_m") / periods);
  }
  f->max_step_m = std::max(f->max_step_m, l.Get("odom_step_m") / periods);
  f->max_step_deg = std::max(f->max_step_deg, l.Get("odom_step_deg") / periods);
}

/// map → odom: its changes, ages and last value.
void AddMapOdom(const Line& l, const AgeCheck& ages, Figures* f) {
  ++f->map_odom;
  ages.Add(l.Int("stamp_ns"), l.Get("age_ns") * 1e-6, f);
  if (f->map_odom > 1) {
    for (const char* key : {"x", "y", "z", "angle_deg"}) {
      if (l.values.at(key) != f->last_map_odom.values.at(key)) {
        ++f->changes;
        break;
      }
    }
  }
  f->last_map_odom = l;
}

Figures Summarize(const std::vector<Line>& lines,
                  const test::LiveDriveResult& r,
                  double imu_period_s) {
  const AgeCheck ages(r);
  Figures f;
  for (const Line& l : lines) {
    if (l.kind == "tf_check") AddPose(l, ages, imu_period_s, &f);
    if (l.kind == "map_odom") AddMapOdom(l, ages, &f);
  }
  return f;
}

TEST(RuntimeFastDdsTf, TheTfChainIsThePublishedPoseAndMapOdomTakesTheLoopCorrections) {
  const auto wall_start = std::chrono::steady_clock::now();
  test::LiveDrive drive;
  drive.dds_domain = kDomain;
  drive.scenario = "short";
  drive.duration_s = 60.0;
  Eigen::Isometry3d T_imu_base = Eigen::Isometry3d::Identity();
  drive.adjust_setup = [&T_imu_base](sim::SimSetup* s) { T_imu_base = s->wheel.T_imu_base; };
  drive.adjust_config = [&T_imu_base](DaemonConfig* c) {
    c->ipc.stamp_clock = "realtime";  // ROS time, what the reader compares with
    c->loop_closure.enabled = true;
    c->loop_closure.min_separation_s = 6.0;  // loops within the minute (file comment)
    // A base frame apart from the IMU (the simulated chassis'), so that odom → base_link,
    // base_link → imu_link and the pose are not the IMU's own.
    c->window.wheel.T_imu_base = estimator::ExtrinsicConfig::FromIsometry(T_imu_base);
  };
  ChildProcess reader({::swlio::test::ToolPath("swlio-fastdds-echo").string(), "--profile",
                       (::swlio::test::SourceDir() / "config" / "fastdds-loopback.xml").string(),
                       "--domain", std::to_string(kDomain), "--tf-check", "--timeout", "300"});
  ASSERT_TRUE(reader.running());
  std::string ready;
  ASSERT_TRUE(reader.ReadLine(&ready, 20.0)) << "the Fast DDS reader did not start";
  for (const char* topic :
       {"rt/tf=tf2_msgs::msg::dds_::TFMessage_", "rt/tf_static=tf2_msgs::msg::dds_::TFMessage_",
        "rt/swlio/pose=geometry_msgs::msg::dds_::PoseWithCovarianceStamped_"}) {
    ASSERT_NE(ready.find(topic), std::string::npos) << ready;
  }
  const auto kept = ::swlio::test::MakeTempDir("fastdds-tf") / "tf_check.txt";
  std::cout << "[ tf ] the reader's lines: " << kept.string()
            << " (SWLIO_KEEP_TEST_DIRS=1 keeps them)\n";
  LineCollector collector(&reader, kept);
  const test::LiveDriveResult r = test::RunLiveDrive(drive);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the last samples' lines
  const std::vector<Line> lines = collector.Stop();
  ASSERT_TRUE(r.sim_ok) << r.error;
  ASSERT_TRUE(r.setup.has_value());

  // /tf_static: base_link → imu_link and → lidar_link, as configured.
  const Eigen::Isometry3d T_imu_lidar = r.setup->lidar.T_imu_lidar;
  std::map<std::string, Eigen::Isometry3d> statics;
  double static_age_ms = 0.0;
  for (const Line& l : lines) {
    if (l.kind != "tf_static") continue;
    EXPECT_EQ(l.values.at("parent"), "base_link");
    statics[l.values.at("child")] = StaticOf(l);
    static_age_ms = std::max(static_age_ms, std::abs(l.Get("age_ns")) * 1e-6);
  }
  ASSERT_EQ(statics.count("imu_link"), 1u) << "no base_link → imu_link on /tf_static";
  ASSERT_EQ(statics.count("lidar_link"), 1u) << "no base_link → lidar_link on /tf_static";
  const Eigen::Isometry3d T_base_imu = T_imu_base.inverse();
  const Eigen::Isometry3d T_base_lidar = T_base_imu * T_imu_lidar;
  EXPECT_LT((statics["imu_link"].translation() - T_base_imu.translation()).norm(), 1e-9);
  EXPECT_LT(AngleDeg(statics["imu_link"], T_base_imu), 1e-6);
  EXPECT_LT((statics["lidar_link"].translation() - T_base_lidar.translation()).norm(), 1e-9);
  EXPECT_LT(AngleDeg(statics["lidar_link"], T_base_lidar), 1e-6);

  // Each pose: composed == published; the stamps' ages; odom → base_link's steps.
  const double imu_period_s = 1.0 / r.setup->imu.rate_hz;
  const auto [v_max, w_max] = MaxBaseRates(*r.setup, T_imu_base, sim::SimDuration(*r.setup));
  // One IMU period's motion at the route's top speed and turn rate, plus what taking in a newly
  // optimized state's correction may add per period (imu_rate_propagator.h: at most
  // estimator.output_rebase_rate_* × period, the rotation's part also at the base's lever arm),
  // plus 0.2 mm / 0.005° for the estimate's own velocity error. From the first pose on: the
  // output never jumps (before re-basing it stepped by up to 10 mm after initialization).
  const estimator::EstimatorConfig& e = r.config.estimator;
  const double lever_m = T_imu_base.translation().norm();
  const double step_bound_m =
      (v_max + e.output_rebase_rate_mps + e.output_rebase_rate_radps * lever_m) * imu_period_s +
      2e-4;
  const double step_bound_deg =
      (w_max + e.output_rebase_rate_radps) * imu_period_s * 180.0 / M_PI + 0.005;
  const Figures f = Summarize(lines, r, imu_period_s);
  const LoopClosureCounters& loops = r.final.loop_closure;
  std::cout << "[ tf ] poses " << f.poses << " (daemon's own subscriber: " << r.poses.size()
            << "), matched " << f.matched << "; composed − published: max " << f.max_pos_m * 1e3
            << " mm, " << f.max_rot_deg << " deg\n"
            << "[ tf ] odom → base_link step per IMU period: max " << f.max_step_m * 1e3 << " mm, "
            << f.max_step_deg << " deg (bound " << step_bound_m * 1e3 << " mm, " << step_bound_deg
            << " deg; v_max " << v_max << " m/s, w_max " << w_max << " rad/s); steps over more "
            << "than one period: " << f.long_steps << "; in the first 5 s: max "
            << f.settling_step_m * 1e3 << " mm\n"
            << "[ tf ] stamp age max " << f.max_age_ms << " ms (/tf_static " << static_age_ms
            << " ms); poses the daemon wrote over 40 ms late: " << f.daemon_late << " (its worst "
            << f.max_daemon_age_ms << " ms)\n"
            << "[ tf ] map → odom samples " << f.map_odom << ", changes " << f.changes
            << "; loops accepted " << loops.accepted << " of " << loops.attempts << ", correction "
            << loops.correction_m * 1e3 << " mm, " << loops.correction_rad * 180.0 / M_PI
            << " deg\n";
  for (const auto& [reason, n] : f.unmatched)
    std::cout << "[ tf ] unmatched: " << reason << " " << n << "\n";

  ASSERT_GT(r.poses.size(), 5000u) << "poses over most of the drive";
  // KEEP_LAST 10 on the pose, as ROS 2's default: a reader short of CPU for 25 ms loses poses
  // (96.4 and 98.5 % reached it on the loaded machine).
  EXPECT_GE(f.matched, r.poses.size() * 90 / 100) << "the reader composed most poses";
  EXPECT_LE(f.max_pos_m, 1e-3);
  EXPECT_LE(f.max_rot_deg, 0.01);
  // Timing holds only when the simulator itself was on time: a CI machine starved it (and
  // the daemon) for hundreds of ms, ctest -j2 beside 4 CPU hogs: stamps 55 ms old, and after
  // seconds of IMU-only propagation the next sweep moved odom → base_link by 74 mm. The age
  // bound is a sanity bound against stamps on another clock (seconds off), not a latency
  // figure: with the simulator on time, ctest -j2 beside two compilers gave 59.7 ms.
  if (r.stats.max_lateness_ms < 200.0) {
    EXPECT_LE(f.max_age_ms, 150.0) << "every stamp within 150 ms of the reader's CLOCK_REALTIME";
    EXPECT_LE(f.daemon_late, f.poses / 20) << "the daemon itself published late";
    EXPECT_LE(f.max_step_m, step_bound_m) << "odom → base_link jumped";
    EXPECT_LE(f.max_step_deg, step_bound_deg) << "odom → base_link jumped";
  } else {
    std::cout << "[ tf ] timing not checked: the simulator sent up to " << r.stats.max_lateness_ms
              << " ms late\n";
  }
  // The loop corrections: applied (accepted) and absorbed by map → odom, whose last value is
  // the correction the loop-closure thread holds.
  ASSERT_GE(loops.accepted, 1u) << "no loop closed on this drive";
  EXPECT_GE(f.changes, 1u) << "map → odom never changed";
  ASSERT_GT(f.map_odom, 0u);
  const double last_m =
      std::hypot(f.last_map_odom.Get("x"), f.last_map_odom.Get("y"), f.last_map_odom.Get("z"));
  EXPECT_GT(loops.correction_m, 0.0);
  EXPECT_NEAR(last_m, loops.correction_m, 1e-3);
  EXPECT_NEAR(f.last_map_odom.Get("angle_deg"), loops.correction_rad * 180.0 / M_PI, 0.01);
  std::cout << "[ tf ] wall time "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count()
            << " s\n";
}

#else

TEST(RuntimeFastDdsTf, TheTfChainIsThePublishedPoseAndMapOdomTakesTheLoopCorrections) {
  GTEST_SKIP() << "swlio-fastdds-echo not built (libfastrtps-dev / fastddsgen missing: "
                  "scripts/install-deps)";
}

#endif

}  // namespace
}  // namespace swlio::daemon

// Estimator values → ROS 2-shaped messages: pose, body-frame twist, covariance order; the robot
// base's pose, twist and covariance from the IMU's state through a non-trivial T_imu_base,
// against numbers worked out by hand and against finite differences; the static transforms.

#include "swlio/daemon/output/message_conversion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "swlio/daemon/pipeline/propagator_thread.h"
#include "swlio/daemon/runtime/health.h"

namespace swlio::daemon {
namespace {

State Yawed90(const Eigen::Vector3d& p, const Eigen::Vector3d& v_world) {
  State s;
  s.t_ns = 1'234'567'890'123;
  s.T_world_imu.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  s.T_world_imu.translation() = p;
  s.vel_world = v_world;
  return s;
}

TEST(MessageConversion, OdometryCarriesPoseInWorldAndTwistInTheBody) {
  estimator::StateCovariance c;
  c.valid = true;
  for (int i = 0; i < estimator::kStateCovSize; ++i) c.P(i, i) = 0.01 * (i + 1);
  c.P(0, 3) = c.P(3, 0) = 0.001;
  const State s = Yawed90({1, 2, 3}, {0, 1.5, 0});  // moving along world y = body x
  const ipc::Odometry m =
      ToOdometryMessage(s, {0, 0, 0.2}, c, Eigen::Isometry3d::Identity(), "map", "imu_link");
  EXPECT_EQ(m.t_ns, s.t_ns);
  EXPECT_EQ(m.frame_id, "map");
  EXPECT_EQ(m.child_frame_id, "imu_link");
  EXPECT_DOUBLE_EQ(m.pose.position_m[2], 3.0);
  EXPECT_NEAR(m.pose.orientation_xyzw[2], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m.pose.orientation_xyzw[3], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m.twist.linear_mps[0], 1.5, 1e-12);
  EXPECT_NEAR(m.twist.linear_mps[1], 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.twist.angular_radps[2], 0.2);
  EXPECT_DOUBLE_EQ(m.pose_covariance[0], 0.01);          // x
  EXPECT_DOUBLE_EQ(m.pose_covariance[6 * 3 + 3], 0.04);  // rotation about X
  EXPECT_DOUBLE_EQ(m.pose_covariance[3], 0.001);         // x–rotX, row-major
  // Body-frame velocity covariance: world P_vv = diag(0.07, 0.08, 0.09) rotated by −90° yaw.
  EXPECT_NEAR(m.twist_covariance[0], 0.08, 1e-12);
  EXPECT_NEAR(m.twist_covariance[7], 0.07, 1e-12);
}

Eigen::Isometry3d Pose(const Eigen::Vector3d& p, double yaw_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
  T.translation() = p;
  return T;
}

Eigen::Isometry3d FromMsg(const ipc::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const auto& q = p.orientation_xyzw;
  T.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.position_m[0], p.position_m[1], p.position_m[2]);
  return T;
}

// The base 0.4 m behind and 0.3 m below the IMU, turned 90° left (base x = IMU y). The IMU at
// (1, 2, 3) yawed 90°, driving forward (IMU x = world y) at 1.5 m/s, turning left at 0.2 rad/s.
// By hand: lever arm in the world R_wi·p_ib = Rz(90°)(−0.4, 0, −0.3) = (0, −0.4, −0.3), so the
// base is at (1, 1.6, 2.7) yawed 180°; v_imu = (1.5, 0, 0), ω × p_ib = (0, −0.08, 0) (the base
// behind the IMU swings right), in base axes (y, −x): (−0.08, −1.5, 0); ω_base = (0, 0, 0.2).
TEST(MessageConversion, BaseMotionFollowsTheLeverArmAndTheBaseAxes) {
  const State s = Yawed90({1, 2, 3}, {0, 1.5, 0});
  const Eigen::Isometry3d T_imu_base = Pose({-0.4, 0.0, -0.3}, M_PI / 2);
  const Eigen::Vector3d gyro_imu(0.0, 0.0, 0.2);
  const BaseMotion b = ToBase(s, gyro_imu, T_imu_base);
  EXPECT_LT((b.T_world_base.translation() - Eigen::Vector3d(1.0, 1.6, 2.7)).norm(), 1e-12);
  EXPECT_LT((b.T_world_base.linear() - Pose({0, 0, 0}, M_PI).linear()).norm(), 1e-12);
  EXPECT_LT((b.vel_base_mps - Eigen::Vector3d(-0.08, -1.5, 0.0)).norm(), 1e-12);
  EXPECT_LT((b.gyro_base_radps - Eigen::Vector3d(0.0, 0.0, 0.2)).norm(), 1e-12);

  // Finite differences of the base pose along the IMU's motion (constant v_world and ω_imu).
  const double dt = 1e-6;
  State later = s;
  later.T_world_imu.translation() += s.vel_world * dt;
  later.T_world_imu.linear() =
      s.T_world_imu.linear() * Eigen::AngleAxisd(0.2 * dt, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Isometry3d T0 = BasePose(s.T_world_imu, T_imu_base);
  const Eigen::Isometry3d T1 = BasePose(later.T_world_imu, T_imu_base);
  const Eigen::Vector3d v_numeric =
      T0.linear().transpose() * (T1.translation() - T0.translation()) / dt;
  EXPECT_LT((v_numeric - b.vel_base_mps).norm(), 1e-6) << v_numeric.transpose();
  const Eigen::AngleAxisd turn(T0.linear().transpose() * T1.linear());
  EXPECT_LT((turn.axis() * turn.angle() / dt - b.gyro_base_radps).norm(), 1e-6);

  // The odometry message carries the same, in the named frames.
  estimator::StateCovariance c;
  c.valid = true;
  for (int i = 0; i < estimator::kStateCovSize; ++i) c.P(i, i) = 0.01;
  for (int i = 3; i < 6; ++i) c.P(i, i) = 0.04;
  const ipc::Odometry m = ToOdometryMessage(s, gyro_imu, c, T_imu_base, "odom", "base_link");
  EXPECT_EQ(m.frame_id, "odom");
  EXPECT_EQ(m.child_frame_id, "base_link");
  EXPECT_LT((FromMsg(m.pose).matrix() - T0.matrix()).norm(), 1e-12);
  EXPECT_NEAR(m.twist.linear_mps[0], -0.08, 1e-12);
  EXPECT_NEAR(m.twist.linear_mps[1], -1.5, 1e-12);
  EXPECT_NEAR(m.twist.angular_radps[2], 0.2, 1e-12);
  // Position covariance at the base: Σp + [a]× Σθ [a]×ᵀ with a = (0, −0.4, −0.3), Σθ = 0.04 I:
  // 0.01 + 0.04·(|a|² I − a aᵀ). Cross terms −[a]× Σθ: δp_x = −0.3 δθ_y + 0.4 δθ_z.
  EXPECT_NEAR(m.pose_covariance[0], 0.02, 1e-12);             // x: 0.01 + 0.04 · 0.25
  EXPECT_NEAR(m.pose_covariance[6 * 1 + 1], 0.0136, 1e-12);   // y: 0.01 + 0.04 · 0.09
  EXPECT_NEAR(m.pose_covariance[6 * 2 + 2], 0.0164, 1e-12);   // z: 0.01 + 0.04 · 0.16
  EXPECT_NEAR(m.pose_covariance[6 * 1 + 2], -0.0048, 1e-12);  // y–z: −0.04 · 0.12
  EXPECT_NEAR(m.pose_covariance[6 * 0 + 4], -0.012, 1e-12);   // x–rotY
  EXPECT_NEAR(m.pose_covariance[6 * 0 + 5], 0.016, 1e-12);    // x–rotZ
  EXPECT_NEAR(m.pose_covariance[6 * 4 + 0], -0.012, 1e-12);   // symmetric
  EXPECT_NEAR(m.pose_covariance[6 * 5 + 5], 0.04, 1e-12);     // rotation unchanged
}

// base_link → imu is T_imu_base⁻¹: the IMU 0.4 m ahead along IMU x = base −y, 0.3 m above;
// base_link → lidar adds T_imu_lidar (0.1 m ahead of, 0.2 m above the IMU): (0, −0.5, 0.5).
TEST(MessageConversion, StaticTransformsPlaceTheSensorsOnTheBase) {
  OutputFrames frames;
  frames.T_imu_base = Pose({-0.4, 0.0, -0.3}, M_PI / 2);
  frames.T_imu_lidar = Pose({0.1, 0.0, 0.2}, 0.0);
  const ipc::TFMessage tf = StaticTransforms(42, frames);
  ASSERT_EQ(tf.transforms.size(), 2u);
  const ipc::TransformStamped& imu = tf.transforms[0];
  const ipc::TransformStamped& lidar = tf.transforms[1];
  EXPECT_EQ(imu.t_ns, 42);
  EXPECT_EQ(imu.frame_id, "base_link");
  EXPECT_EQ(imu.child_frame_id, "imu_link");
  EXPECT_EQ(lidar.frame_id, "base_link");
  EXPECT_EQ(lidar.child_frame_id, "lidar_link");
  EXPECT_NEAR(imu.transform.translation_m[0], 0.0, 1e-12);
  EXPECT_NEAR(imu.transform.translation_m[1], -0.4, 1e-12);
  EXPECT_NEAR(imu.transform.translation_m[2], 0.3, 1e-12);
  EXPECT_NEAR(imu.transform.rotation_xyzw[2], -std::sqrt(0.5), 1e-12);  // yaw −90°
  EXPECT_NEAR(imu.transform.rotation_xyzw[3], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(lidar.transform.translation_m[0], 0.0, 1e-12);
  EXPECT_NEAR(lidar.transform.translation_m[1], -0.5, 1e-12);
  EXPECT_NEAR(lidar.transform.translation_m[2], 0.5, 1e-12);
}

TEST(MessageConversion, ImuRateCovarianceGrowsWithTheTimeSinceTheLastState) {
  estimator::StateCovariance c;
  c.valid = true;
  c.P.setIdentity();
  c.P *= 1e-4;
  EXPECT_DOUBLE_EQ(GrownPoseCovariance(c, 0.0)[0], 1e-4);
  EXPECT_DOUBLE_EQ(GrownPoseCovariance(c, 2.0)[0], 1e-4 + 1e-4 * 4.0);
  EXPECT_DOUBLE_EQ(GrownPoseCovariance(c, 2.0)[6 * 3 + 3], 1e-4) << "attitude unchanged";
  EXPECT_EQ(GrownPoseCovariance(estimator::StateCovariance{}, 1.0)[0], 0.0) << "unknown: zeros";
}

TEST(HealthReporter, ReportsRatesStatesAndDrops) {
  HealthSnapshot a;
  a.t_ns = 1'000'000'000;
  HealthSnapshot b = a;
  b.t_ns = 2'000'000'000;
  b.propagator.samples = 400;
  b.optimizer.lidar.data_packets = 750;
  b.optimizer.lidar.sweeps = 10;
  b.optimizer.tracking = TrackingState::kDegraded;
  QueueCounters q;
  q.name = "poses";
  q.producer = "propagator";
  q.consumer = "publisher";
  q.dropped = 3;
  b.queues = {q};
  HealthReporter r;
  r.Diagnostics(a);
  const ipc::DiagnosticArray d = r.Diagnostics(b);
  // lidar, imu, estimator, queues, time
  ASSERT_EQ(d.status.size(), 5u);
  EXPECT_EQ(d.status[0].level, ipc::DiagnosticLevel::kOk);  // lidar streaming
  EXPECT_EQ(d.status[1].values[0].value, "400.0");          // imu rate_hz
  EXPECT_EQ(d.status[2].message, "degraded");
  EXPECT_EQ(d.status[3].level, ipc::DiagnosticLevel::kWarn);
  EXPECT_EQ(d.status[3].message, "3 dropped");
  EXPECT_EQ(TotalDrops(b), 3u);
  const ipc::DiagnosticArray silent = r.Diagnostics(b);  // nothing new for a second
  EXPECT_EQ(silent.status[0].level, ipc::DiagnosticLevel::kError);
  EXPECT_EQ(silent.status[1].message, "device not open");
}

TEST(HealthReporter, SaysWhyTheEstimatorIsLostWhileItReinitializes) {
  HealthSnapshot s;
  s.t_ns = 1'000'000'000;
  s.optimizer.tracking = TrackingState::kLost;
  s.optimizer.recovering = true;
  s.optimizer.reinitializations = 2;
  s.optimizer.operator_resets = 1;
  s.optimizer.skipped_behind = 7;
  s.optimizer.last_divergence = "speed out of bounds";
  HealthReporter r;
  const ipc::DiagnosticArray d = r.Diagnostics(s);
  EXPECT_EQ(d.status[2].level, ipc::DiagnosticLevel::kError);
  EXPECT_EQ(d.status[2].message,
            "lost: re-initializing after speed out of bounds; degraded: CPU (7 sweeps skipped, "
            "the estimator fell behind)");
  int counted = 0;
  for (const auto& kv : d.status[2].values) {
    counted += kv.key == "reinitializations" && kv.value == "2";
    counted += kv.key == "operator_resets" && kv.value == "1";
  }
  EXPECT_EQ(counted, 2) << "re-initializations and, of those, the operator's resets";
  EXPECT_NE(r.StatusLine(s).find("reinit 2 (operator resets 1)"), std::string::npos);
  EXPECT_NE(r.StatusLine(s).find("skipped behind 7"), std::string::npos);
  bool skipped = false;
  for (const auto& kv : d.status[2].values)
    skipped |= kv.key == "sweeps_skipped_behind" && kv.value == "7";
  EXPECT_TRUE(skipped);
}

TEST(HealthReporter, WarnsWhileASensorClockJumps) {
  HealthSnapshot a;
  a.t_ns = 1'000'000'000;
  a.optimizer.lidar_clock.jumps = 1;  // one before the first report: reported then
  HealthSnapshot b = a;
  b.t_ns = 2'000'000'000;
  b.propagator.samples = 400;
  b.optimizer.lidar.data_packets = 750;
  b.optimizer.lidar_clock.jumps = 3;
  b.optimizer.lidar_clock.offset_ns = -1.5e9;
  b.optimizer.lidar_clock.drift_ppm = 12.0;
  HealthReporter r;
  const HealthRates first = r.Rates(a);
  EXPECT_EQ(first.lidar_clock_jumps, 1u);
  ASSERT_EQ(ClockJumpWarnings(a, first).size(), 1u);
  const HealthRates rates = r.Rates(b);
  EXPECT_EQ(rates.lidar_clock_jumps, 2u);
  EXPECT_EQ(rates.imu_clock_jumps, 0u);
  const std::vector<std::string> w = ClockJumpWarnings(b, rates);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("lidar clock: jumped 2 time(s) since the last status (3 in all)"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("offset now -1.500000 s"), std::string::npos) << w[0];

  HealthReporter published;
  published.Diagnostics(a);
  const ipc::DiagnosticArray d = published.Diagnostics(b);
  EXPECT_EQ(d.status[0].level, ipc::DiagnosticLevel::kWarn);
  EXPECT_EQ(d.status[0].message, "streaming; clock jumped");
  EXPECT_EQ(d.status[1].level, ipc::DiagnosticLevel::kOk);  // the IMU's clock did not jump
  b.t_ns += 1'000'000'000;
  b.propagator.samples += 400;
  b.optimizer.lidar.data_packets += 750;
  const ipc::DiagnosticArray calm = published.Diagnostics(b);  // no new jump: OK again
  EXPECT_EQ(calm.status[0].level, ipc::DiagnosticLevel::kOk);
  EXPECT_TRUE(ClockJumpWarnings(b, r.Rates(b)).empty());
}

TEST(HealthReporter, SaysWhetherTheRobotIsTakenToStandStill) {
  HealthSnapshot s;
  s.t_ns = 1'000'000'000;
  s.optimizer.standing_still = true;
  s.optimizer.standstill_sweeps = 42;
  const ipc::DiagnosticArray d = HealthReporter().Diagnostics(s);
  int found = 0;
  for (const auto& kv : d.status[2].values) {
    found += kv.key == "standing_still" && kv.value == "true";
    found += kv.key == "standstill_sweeps" && kv.value == "42";
  }
  EXPECT_EQ(found, 2);
}

TEST(HealthReporter, SaysHowLongTheImuAloneHasCarriedTheState) {
  HealthSnapshot s;
  s.t_ns = 1'000'000'000;
  s.optimizer.tracking = TrackingState::kDegraded;
  s.optimizer.imu_only_s = 1.25;
  HealthReporter r;
  const ipc::DiagnosticArray d = r.Diagnostics(s);
  EXPECT_EQ(d.status[2].level, ipc::DiagnosticLevel::kWarn);
  EXPECT_EQ(d.status[2].message, "degraded: no LiDAR sweeps, IMU only for 1.2 s");
}

std::string EstimatorValue(const ipc::DiagnosticArray& d, const std::string& key) {
  for (const auto& kv : d.status[2].values) {
    if (kv.key == key) return kv.value;
  }
  return "(missing)";
}

TEST(HealthReporter, ReportsHowOldTheLastProcessedSweepIs) {
  HealthSnapshot s;
  s.t_ns = 10'000'000'000;
  HealthReporter r;
  EXPECT_EQ(EstimatorValue(r.Diagnostics(s), "sweep_age_s"), "none");
  s.optimizer.last_sweep_end_host_ns = 7'500'000'000;
  EXPECT_EQ(EstimatorValue(r.Diagnostics(s), "sweep_age_s"), "2.50");
}

}  // namespace
}  // namespace swlio::daemon

// The health's time status: which clock the stamps are on, the offset from the daemon's
// monotonic time, and a warning in the report after each wall-clock step.

#include "swlio/daemon/runtime/health.h"

#include <gtest/gtest.h>

#include <string>

namespace swlio::daemon {
namespace {

const ipc::DiagnosticStatus* Find(const ipc::DiagnosticArray& a, const std::string& name) {
  for (const ipc::DiagnosticStatus& s : a.status) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::string Value(const ipc::DiagnosticStatus& s, const std::string& key) {
  for (const ipc::KeyValue& kv : s.values) {
    if (kv.key == key) return kv.value;
  }
  return "(absent)";
}

TEST(HealthReporter, ReportsTheStampClockAndWarnsAfterAWallClockStep) {
  HealthSnapshot a;
  a.t_ns = 1'000'000'000;
  a.stamp_clock.offset_ns = 1'780'000'000'123'456'789;
  HealthSnapshot b = a;
  b.t_ns = 2'000'000'000;
  b.stamp_clock.offset_ns += 10'000'000'000;
  b.stamp_clock.steps = 1;
  b.stamp_clock.last_step_ns = 10'000'000'000;
  HealthReporter r;
  const ipc::DiagnosticArray first = r.Diagnostics(a);
  const ipc::DiagnosticStatus* t = Find(first, "swlio: time");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->level, ipc::DiagnosticLevel::kOk);
  EXPECT_EQ(t->message, "stamps on CLOCK_REALTIME");
  EXPECT_EQ(Value(*t, "stamp_clock"), "realtime");
  EXPECT_EQ(Value(*t, "realtime_minus_monotonic_s"), "1780000000.123457");
  EXPECT_EQ(Value(*t, "wall_clock_steps"), "0");

  const ipc::DiagnosticArray stepped = r.Diagnostics(b);
  t = Find(stepped, "swlio: time");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->level, ipc::DiagnosticLevel::kWarn);
  EXPECT_EQ(t->message, "stamps on CLOCK_REALTIME; wall clock stepped by +10.000000 s");
  EXPECT_EQ(Value(*t, "wall_clock_steps"), "1");
  EXPECT_EQ(Value(*t, "last_step_s"), "+10.000000");

  HealthSnapshot c = b;  // a second later, no new step: OK again, the count kept
  c.t_ns = 3'000'000'000;
  const ipc::DiagnosticArray later = r.Diagnostics(c);
  t = Find(later, "swlio: time");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->level, ipc::DiagnosticLevel::kOk);
  EXPECT_EQ(Value(*t, "wall_clock_steps"), "1");
}

TEST(HealthReporter, SaysWhenTheStampsAreMonotonic) {
  HealthSnapshot s;
  s.stamp_clock.realtime = false;
  HealthReporter r;
  const ipc::DiagnosticArray a = r.Diagnostics(s);
  const ipc::DiagnosticStatus* t = Find(a, "swlio: time");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->message, "stamps on CLOCK_MONOTONIC");
  EXPECT_EQ(Value(*t, "stamp_clock"), "monotonic");
}

// What went out over DDS, /tf included (REP 105 consumers depend on it), and a refused pose hint
// as a warning with its reason (issue 34).
TEST(HealthReporter, CountsTheDdsSamplesAndWarnsOfARefusedHint) {
  HealthSnapshot s;
  s.t_ns = 40'000'000'000;
  s.publisher.poses = 4000;
  s.publisher.transforms = 4011;
  s.publisher.odometry = 100;
  s.publisher.odom_odometry = 100;
  s.publisher.paths = 7;
  s.localization.enabled = true;
  s.localization.state = estimator::LocalizationState::kTracking;
  s.localization.hints = 2;
  s.localization.hints_refused = 1;
  s.localization.last_hint = "refused: no map node within 30 m";
  s.localization.last_hint_refused = true;
  s.localization.last_hint_t_ns = 35'000'000'000;
  HealthReporter r;
  const ipc::DiagnosticArray a = r.Diagnostics(s);
  const ipc::DiagnosticStatus* q = Find(a, "swlio: queues");
  ASSERT_NE(q, nullptr);
  EXPECT_EQ(Value(*q, "dds_samples"),
            "poses 4000, tf 4011, odometry 100, odom_odometry 100, paths 7, tf_static re-sent 0");
  const ipc::DiagnosticStatus* l = Find(a, "swlio: localization");
  ASSERT_NE(l, nullptr);
  EXPECT_EQ(l->level, ipc::DiagnosticLevel::kWarn);
  EXPECT_EQ(l->message, "pose hint refused: no map node within 30 m; still localized as before");
  EXPECT_EQ(Value(*l, "hints_refused"), "1");
  s.t_ns = 70'000'000'000;  // 35 s later: news no more, the value kept
  const ipc::DiagnosticArray b = r.Diagnostics(s);
  const ipc::DiagnosticStatus* later = Find(b, "swlio: localization");
  ASSERT_NE(later, nullptr);
  EXPECT_EQ(later->level, ipc::DiagnosticLevel::kOk);
  EXPECT_EQ(Value(*later, "last_hint"), "refused: no map node within 30 m");
}

// The LiDAR–IMU time offset: the applied one always, the window's own only where it estimates
// one (estimator.window.time_offset.window_prior_sigma_s).
TEST(HealthReporter, ReportsTheWindowsTimeOffsetOnlyWhereItIsEstimated) {
  HealthSnapshot s;
  s.optimizer.time_offset.offset_s = -0.0051;
  HealthReporter r;
  const ipc::DiagnosticArray a = r.Diagnostics(s);
  const ipc::DiagnosticStatus* e = Find(a, "swlio: estimator");
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(Value(*e, "imu_time_offset_ms"), "-5.10");
  EXPECT_EQ(Value(*e, "imu_time_offset_window_ms"), "(absent)");
  s.optimizer.time_offset.window_offset_s = -0.00497;
  const ipc::DiagnosticArray b = r.Diagnostics(s);
  const ipc::DiagnosticStatus* w = Find(b, "swlio: estimator");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(Value(*w, "imu_time_offset_window_ms"), "-4.97");
}

}  // namespace
}  // namespace swlio::daemon

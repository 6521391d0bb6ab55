// The status report's events: the fields of `status`, and which warnings go with it.

#include "swlio/daemon/runtime/health_events.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace swlio::daemon {
namespace {

std::string Field(const HealthEvent& e, const std::string& name) {
  for (const EventField& f : e.fields) {
    if (f.name == name) return f.value;
  }
  return "(absent)";
}

HealthSnapshot Busy() {
  HealthSnapshot s;
  s.t_ns = 5'000'000'000;
  s.optimizer.tracking = TrackingState::kDegraded;
  s.optimizer.processed = 48;
  s.optimizer.reinitializations = 2;
  s.optimizer.skipped_behind = 9;
  s.optimizer.last_update_ms = 31.26;
  s.optimizer.lidar_clock.jumps = 1;
  s.optimizer.lidar_clock.offset_ns = 2.5e9;
  s.propagator.clock_jumps = 0;
  s.stamp_clock.steps = 1;
  s.queues.push_back({"lidar", "lidar_rx", "optimizer", 64, 1000, 3, 0, 64});
  s.queues.push_back({"imu", "imu_rx", "propagator", 4096, 20000, 0, 0, 12});
  return s;
}

TEST(HealthEvents, StatusCarriesTheStateAndCounters) {
  const HealthSnapshot s = Busy();
  HealthRates r;
  r.sweeps_hz = 9.96;
  r.imu_hz = 400.4;
  const std::vector<HealthEvent> events = StatusEvents(s, r, "status line text");
  ASSERT_FALSE(events.empty());
  const HealthEvent& status = events.front();
  EXPECT_EQ(status.event, "status");
  EXPECT_EQ(status.level, spdlog::level::info);
  EXPECT_EQ(status.message, "status line text");
  EXPECT_EQ(Field(status, "STATE"), "degraded");
  EXPECT_EQ(Field(status, "SWEEPS"), "48");
  EXPECT_EQ(Field(status, "SWEEPS_HZ"), "10.0");
  EXPECT_EQ(Field(status, "IMU_HZ"), "400");
  EXPECT_EQ(Field(status, "REINITIALIZATIONS"), "2");
  EXPECT_EQ(Field(status, "SKIPPED_BEHIND"), "9");
  EXPECT_EQ(Field(status, "DROPS"), "3");
  EXPECT_EQ(Field(status, "LIDAR_CLOCK_JUMPS"), "1");
  EXPECT_EQ(Field(status, "WALL_CLOCK_STEPS"), "1");
  EXPECT_EQ(Field(status, "UPDATE_MS"), "31.3");
  EXPECT_EQ(Field(status, "LOC_STATE"), "(absent)");  // not localizing
  for (const EventField& f : status.fields) {
    EXPECT_EQ(f.name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_"), std::string::npos)
        << f.name;
  }
}

TEST(HealthEvents, WarningsFollowTheStatus) {
  const HealthSnapshot s = Busy();
  HealthRates r;
  r.lidar_clock_jumps = 1;  // since the previous report
  r.sweeps_skipped_behind = 4;
  const std::vector<HealthEvent> events = StatusEvents(s, r, "status");
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[1].event, "queue_drops");
  EXPECT_EQ(events[1].level, spdlog::level::warn);
  EXPECT_EQ(events[1].message, "queue lidar (lidar_rx -> optimizer): 3 dropped, high water 64/64");
  EXPECT_EQ(Field(events[1], "QUEUE"), "lidar");
  EXPECT_EQ(Field(events[1], "DROPPED"), "3");
  EXPECT_EQ(events[2].event, "clock_jump");
  EXPECT_EQ(events[2].message, ClockJumpWarnings(s, r).at(0));
  EXPECT_EQ(Field(events[2], "SENSOR"), "lidar");
  EXPECT_EQ(Field(events[2], "OFFSET_S"), "2.500000");
  EXPECT_EQ(events[3].event, "estimator_behind");
  EXPECT_EQ(Field(events[3], "SKIPPED"), "4");
  EXPECT_EQ(Field(events[3], "SKIPPED_TOTAL"), "9");
  EXPECT_NE(events[3].message.find("degraded: CPU: 4 sweeps skipped"), std::string::npos);
}

TEST(HealthEvents, ImuClockJumpAloneIsTheImus) {
  HealthSnapshot s;
  s.propagator.clock_jumps = 3;
  HealthRates r;
  r.imu_clock_jumps = 1;
  const std::vector<HealthEvent> events = StatusEvents(s, r, "status");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[1].event, "clock_jump");
  EXPECT_EQ(Field(events[1], "SENSOR"), "imu");
  EXPECT_EQ(Field(events[1], "JUMPS_TOTAL"), "3");
  EXPECT_EQ(events[1].message.rfind("imu clock:", 0), 0u) << events[1].message;
}

}  // namespace
}  // namespace swlio::daemon

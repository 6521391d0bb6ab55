// Incident events from the health (incident_detector.h): edges, not levels; one reason at most
// every kRepeatNs; the recorder's own queue drops are no incident.

#include "swlio/daemon/blackbox/incident_detector.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "swlio/estimator/map/map_localizer.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kSec = 1'000'000'000;

std::vector<std::string> Reasons(const std::vector<IncidentEvent>& events) {
  std::vector<std::string> out;
  for (const IncidentEvent& e : events) out.push_back(e.reason);
  return out;
}

/// A streaming daemon at second `t`: both sensors' counters move.
HealthSnapshot Streaming(int64_t t) {
  HealthSnapshot s;
  s.lidar_rx.datagrams = 840 * static_cast<uint64_t>(t);
  s.propagator.samples = 400 * static_cast<uint64_t>(t);
  return s;
}

TEST(IncidentDetector, ASilentLidarIsOneEventUntilItStreamsAgain) {
  IncidentDetector d;
  for (int64_t t = 1; t <= 3; ++t) EXPECT_TRUE(d.Update(Streaming(t), t * kSec, 0).empty());
  HealthSnapshot s = Streaming(3);
  std::vector<std::string> seen;
  for (int64_t t = 4; t <= 8; ++t) {  // the LiDAR stops after second 3
    s.propagator.samples += 400;
    for (const std::string& r : Reasons(d.Update(s, t * kSec, 0)))
      seen.push_back(r + "@" + std::to_string(t));
  }
  EXPECT_EQ(seen, std::vector<std::string>{"lidar_silent@4"});
  // Streams again, then falls silent again after the repeat interval: a new event.
  for (int64_t t = 9; t <= 20; ++t) {
    s.propagator.samples += 400;
    s.lidar_rx.datagrams += t <= 15 ? 840 : 0;
    for (const std::string& r : Reasons(d.Update(s, t * kSec, 0)))
      seen.push_back(r + "@" + std::to_string(t));
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"lidar_silent@4", "lidar_silent@16"}));
}

TEST(IncidentDetector, NothingBeforeASensorEverStreamed) {
  IncidentDetector d;
  for (int64_t t = 1; t <= 10; ++t) EXPECT_TRUE(d.Update(HealthSnapshot{}, t * kSec, 0).empty());
}

TEST(IncidentDetector, DivergenceUnplugClockJumpAndBehindAreEvents) {
  IncidentDetector d;
  d.Update(Streaming(1), kSec, 0);
  HealthSnapshot s = Streaming(2);
  s.optimizer.reinitializations = 1;
  s.optimizer.last_divergence = "lidar_lost";
  s.imu_rx.disconnects = 1;
  s.propagator.clock_jumps = 1;
  s.optimizer.skipped_behind = 3;
  const std::vector<IncidentEvent> e = d.Update(s, 2 * kSec, 1'780'000'000 * kSec);
  EXPECT_EQ(Reasons(e), (std::vector<std::string>{"imu_silent", "clock_jump", "divergence",
                                                  "estimator_behind"}));
  for (const IncidentEvent& x : e) {
    EXPECT_EQ(x.t_ns, 2 * kSec);
    EXPECT_EQ(x.realtime_ns, 1'780'000'000 * kSec);
  }
  EXPECT_NE(e[2].detail.find("lidar_lost"), std::string::npos) << e[2].detail;
}

TEST(IncidentDetector, AnOperatorsResetIsNoDivergence) {
  IncidentDetector d;
  d.Update(Streaming(1), kSec, 0);
  HealthSnapshot s = Streaming(2);
  s.optimizer.reinitializations = 1;  // swlioctl reset
  s.optimizer.operator_resets = 1;
  EXPECT_TRUE(d.Update(s, 2 * kSec, 0).empty());
  s = Streaming(3);
  s.optimizer.reinitializations = 2;  // then a divergence
  s.optimizer.operator_resets = 1;
  EXPECT_EQ(Reasons(d.Update(s, 3 * kSec, 0)), std::vector<std::string>{"divergence"});
}

TEST(IncidentDetector, LidarLossNeedsTenPacketsAndOnePercent) {
  IncidentDetector d;
  HealthSnapshot s = Streaming(1);
  d.Update(s, kSec, 0);
  s = Streaming(2);
  s.optimizer.lidar.missing_packets = 9;  // below the count
  EXPECT_TRUE(d.Update(s, 2 * kSec, 0).empty());
  s = Streaming(3);
  s.optimizer.lidar.missing_packets = 9 + 12;  // 12 of 852: 1.4 %
  EXPECT_EQ(Reasons(d.Update(s, 3 * kSec, 0)), std::vector<std::string>{"lidar_lossy"});
}

TEST(IncidentDetector, TheRecordersOwnDropsAreNoIncident) {
  IncidentDetector d;
  HealthSnapshot s = Streaming(1);
  s.queues = {QueueCounters{}, QueueCounters{}};
  s.queues[0].consumer = "optimizer";
  s.queues[1].consumer = "recorder";
  d.Update(s, kSec, 0);
  s.lidar_rx.datagrams += 840;
  s.propagator.samples += 400;
  s.queues[1].dropped = 100;
  EXPECT_TRUE(d.Update(s, 2 * kSec, 0).empty());
  s.lidar_rx.datagrams += 840;
  s.propagator.samples += 400;
  s.queues[0].dropped = 1;
  EXPECT_EQ(Reasons(d.Update(s, 3 * kSec, 0)), std::vector<std::string>{"queue_drops"});
}

TEST(IncidentDetector, AStalledThreadIsOneEventPerEpisode) {
  IncidentDetector d;
  EXPECT_EQ(Reasons(d.Update(HealthSnapshot{}, kSec, 0, {"optimizer"})),
            std::vector<std::string>{"watchdog"});
  EXPECT_TRUE(d.Update(HealthSnapshot{}, 2 * kSec, 0, {"optimizer"}).empty());
  EXPECT_TRUE(d.Update(HealthSnapshot{}, 3 * kSec, 0, {}).empty());
  EXPECT_EQ(Reasons(d.Update(HealthSnapshot{}, 30 * kSec, 0, {"publisher"})),
            std::vector<std::string>{"watchdog"});
}

TEST(IncidentDetector, LocalizationLostAndLongAmbiguityAreEvents) {
  IncidentDetector d;
  HealthSnapshot s;
  s.localization.enabled = true;
  s.localization.state = estimator::LocalizationState::kConfirming;
  s.localization.hypotheses = 2;
  std::vector<std::string> seen;
  // Confirming from the second look on (the first only sets the baseline): ambiguous 30 s on.
  for (int64_t t = 1; t <= 40; ++t) {
    for (const std::string& r : Reasons(d.Update(s, t * kSec, 0)))
      seen.push_back(r + "@" + std::to_string(t));
  }
  EXPECT_EQ(seen, std::vector<std::string>{"localization_ambiguous@32"});
  s.localization.state = estimator::LocalizationState::kTracking;
  EXPECT_TRUE(d.Update(s, 41 * kSec, 0).empty());
  s.localization.lost = 1;
  s.localization.state = estimator::LocalizationState::kRelocalizing;
  EXPECT_EQ(Reasons(d.Update(s, 42 * kSec, 0)), std::vector<std::string>{"localization_lost"});
}

}  // namespace
}  // namespace swlio::daemon

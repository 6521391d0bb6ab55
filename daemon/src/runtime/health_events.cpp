#include "swlio/daemon/runtime/health_events.h"

#include <spdlog/fmt/fmt.h>

#include "swlio/daemon/pipeline/live_types.h"

namespace swlio::daemon {
namespace {

std::string HealthCount(uint64_t v) { return std::to_string(v); }
std::string HealthFixed(double v, int decimals) { return fmt::format("{:.{}f}", v, decimals); }

std::vector<HealthEvent> QueueDropEvents(const HealthSnapshot& s) {
  std::vector<HealthEvent> out;
  for (const QueueCounters& q : s.queues) {
    if (q.dropped == 0) continue;
    out.push_back({spdlog::level::warn,
                   "queue_drops",
                   fmt::format("queue {} ({} -> {}): {} dropped, high water {}/{}", q.name,
                               q.producer, q.consumer, q.dropped, q.high_water, q.capacity),
                   {{"QUEUE", q.name},
                    {"PRODUCER", q.producer},
                    {"CONSUMER", q.consumer},
                    {"DROPPED", HealthCount(q.dropped)},
                    {"HIGH_WATER", std::to_string(q.high_water)},
                    {"CAPACITY", std::to_string(q.capacity)}}});
  }
  return out;
}

/// ClockJumpWarnings gives one line per sensor that jumped, LiDAR first, then the IMU.
std::vector<HealthEvent> ClockJumpEvents(const HealthSnapshot& s, const HealthRates& r) {
  struct Jump {
    const char* sensor;
    uint64_t jumps;
    uint64_t total;
    double offset_ns;
    double drift_ppm;
  };
  const drivers::ClockModelStats& lidar = s.optimizer.lidar_clock;
  const Jump all[] = {{"lidar", r.lidar_clock_jumps, lidar.jumps, lidar.offset_ns, lidar.drift_ppm},
                      {"imu", r.imu_clock_jumps, s.propagator.clock_jumps,
                       s.propagator.clock_offset_ns, s.propagator.clock_drift_ppm}};
  const std::vector<std::string> lines = ClockJumpWarnings(s, r);
  std::vector<HealthEvent> out;
  for (const Jump& j : all) {
    if (j.jumps == 0 || out.size() >= lines.size()) continue;
    out.push_back({spdlog::level::warn,
                   "clock_jump",
                   lines[out.size()],
                   {{"SENSOR", j.sensor},
                    {"JUMPS", HealthCount(j.jumps)},
                    {"JUMPS_TOTAL", HealthCount(j.total)},
                    {"OFFSET_S", HealthFixed(j.offset_ns * 1e-9, 6)},
                    {"DRIFT_PPM", HealthFixed(j.drift_ppm, 1)}}});
  }
  return out;
}

}  // namespace

std::vector<EventField> StatusFields(const HealthSnapshot& s, const HealthRates& r) {
  std::vector<EventField> f = {
      {"STATE", ToString(s.optimizer.tracking)},
      {"SWEEPS", HealthCount(s.optimizer.processed)},
      {"LIDAR_PACKETS_HZ", HealthFixed(r.lidar_packets_hz, 0)},
      {"SWEEPS_HZ", HealthFixed(r.sweeps_hz, 1)},
      {"IMU_HZ", HealthFixed(r.imu_hz, 0)},
      {"POSE_HZ", HealthFixed(r.poses_hz, 0)},
      {"LIDAR_MISSING_PACKETS", HealthCount(s.optimizer.lidar.missing_packets)},
      {"IMU_CHECKSUM_ERRORS", HealthCount(ImuChecksumErrors(s))},
      {"IMU_GAPS", HealthCount(s.propagator.decode.missing_packets)},
      {"UPDATE_MS", HealthFixed(s.optimizer.last_update_ms, 1)},
      {"MAX_UPDATE_MS", HealthFixed(s.optimizer.max_update_ms, 1)},
      {"DROPS", HealthCount(TotalDrops(s))},
      {"SKIPPED_BEHIND", HealthCount(s.optimizer.skipped_behind)},
      {"REINITIALIZATIONS", HealthCount(s.optimizer.reinitializations)},
      {"LIDAR_CLOCK_JUMPS", HealthCount(s.optimizer.lidar_clock.jumps)},
      {"IMU_CLOCK_JUMPS", HealthCount(s.propagator.clock_jumps)},
      {"WALL_CLOCK_STEPS", HealthCount(s.stamp_clock.steps)},
      {"IMU_READ_LAG_P99_MS", HealthFixed(r.imu_read_lag.p99_ms, 1)},
      {"LIDAR_READ_LAG_P99_MS", HealthFixed(r.lidar_read_lag.p99_ms, 1)},
      {"POSE_LATENCY_P99_MS", HealthFixed(r.pose_latency.p99_ms, 1)},
  };
  if (s.localization.enabled) {
    f.push_back({"LOC_STATE", estimator::ToString(s.localization.state)});
    f.push_back({"LOC_LOST", HealthCount(s.localization.lost)});
  }
  return f;
}

std::vector<HealthEvent> StatusEvents(const HealthSnapshot& now,
                                      const HealthRates& rates,
                                      const std::string& status_line) {
  std::vector<HealthEvent> out;
  out.push_back({spdlog::level::info, "status", status_line, StatusFields(now, rates)});
  for (HealthEvent& e : QueueDropEvents(now)) out.push_back(std::move(e));
  for (HealthEvent& e : ClockJumpEvents(now, rates)) out.push_back(std::move(e));
  if (rates.sweeps_skipped_behind > 0) {
    // The estimator fell behind and shed sweeps: the CPU it gets does not suffice.
    out.push_back(
        {spdlog::level::warn,
         "estimator_behind",
         fmt::format("degraded: CPU: {} sweeps skipped since the last status (the estimator fell "
                     "behind the LiDAR); the IMU-rate pose continues. A busy computer or a CPU "
                     "quota: docs/scheduling.md",
                     rates.sweeps_skipped_behind),
         {{"SKIPPED", HealthCount(rates.sweeps_skipped_behind)},
          {"SKIPPED_TOTAL", HealthCount(now.optimizer.skipped_behind)}}});
  }
  return out;
}

void LogHealthEvents(const std::vector<HealthEvent>& events) {
  for (const HealthEvent& e : events) LogEvent(e.level, e.event, e.message, e.fields);
}

}  // namespace swlio::daemon

#include "swlio/daemon/blackbox/health_row.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>

#include "swlio/estimator/map/map_localizer.h"

namespace swlio::daemon {

const char* const kHealthCsvHeader =
    "t_ns,utc,lidar_datagrams,lidar_bad_packets,lidar_missing_packets,lidar_sweeps,"
    "lidar_clock_offset_ms,lidar_clock_drift_ppm,lidar_clock_jumps,imu_bytes,imu_samples,"
    "imu_checksum_errors,imu_skipped_bytes,imu_disconnects,imu_clock_offset_ms,"
    "imu_clock_drift_ppm,imu_clock_jumps,estimator_tracking,estimator_sweeps,estimator_update_ms,"
    "estimator_max_update_ms,estimator_degenerate_directions,estimator_reinitializations,"
    "estimator_skipped_behind,estimator_imu_only_s,estimator_map_points,loop_nodes,loop_accepted,"
    "loop_rejected,loop_correction_m,loc_state,loc_tracked,loc_lost,loc_hints,poses,"
    "queue_max_fill,queue_dropped,wall_clock_steps,cpu_s,rss_mb,imu_time_offset_ms,"
    "imu_time_offset_sigma_ms,moving_points_removed,estimator_operator_resets";

ProcessUsage ReadProcessUsage() {
  ProcessUsage u;
  rusage r{};
  if (getrusage(RUSAGE_SELF, &r) == 0) {
    u.cpu_s = static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
              static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec) * 1e-6;
  }
  std::ifstream statm("/proc/self/statm");  // size resident ... in pages (proc(5))
  long long size = 0, resident = 0;
  if (statm >> size >> resident) {
    u.rss_mb = static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
  }
  return u;
}

std::string FormatUtc(int64_t realtime_ns, const char* format) {
  const time_t sec = static_cast<time_t>(realtime_ns / 1'000'000'000);
  tm utc{};
  gmtime_r(&sec, &utc);
  char text[64];
  const size_t n = std::strftime(text, sizeof text, format, &utc);
  return std::string(text, n);
}

std::string UtcIso(int64_t realtime_ns) {
  char ms[8];
  std::snprintf(ms, sizeof ms, ".%03dZ", static_cast<int>((realtime_ns / 1'000'000) % 1000));
  return FormatUtc(realtime_ns, "%Y-%m-%dT%H:%M:%S") + ms;
}

namespace {

/// Appends ",value".
template <class T>
void Col(std::string* row, const T& value) {
  row->push_back(',');
  if constexpr (std::is_floating_point_v<T>) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", static_cast<double>(value));
    row->append(text);
  } else if constexpr (std::is_convertible_v<T, std::string>) {
    row->append(value);
  } else {
    row->append(std::to_string(value));
  }
}

double QueueMaxFill(const HealthSnapshot& s) {
  double fill = 0.0;
  for (const QueueCounters& q : s.queues) {
    if (q.capacity > 0)
      fill = std::max(fill, static_cast<double>(q.depth) / static_cast<double>(q.capacity));
  }
  return fill;
}

void SensorColumns(const HealthSnapshot& s, std::string* row) {
  const OptimizerCounters& o = s.optimizer;
  Col(row, s.lidar_rx.datagrams);
  Col(row, o.lidar.bad_packets);
  Col(row, o.lidar.missing_packets);
  Col(row, o.lidar.sweeps);
  Col(row, o.lidar_clock.offset_ns * 1e-6);
  Col(row, o.lidar_clock.drift_ppm);
  Col(row, o.lidar_clock.jumps);
  Col(row, s.imu_rx.bytes);
  Col(row, s.propagator.samples);
  Col(row, ImuChecksumErrors(s));
  Col(row, ImuSkippedBytes(s));
  Col(row, s.imu_rx.disconnects);
  Col(row, s.propagator.clock_offset_ns * 1e-6);
  Col(row, s.propagator.clock_drift_ppm);
  Col(row, s.propagator.clock_jumps);
}

void EstimatorColumns(const HealthSnapshot& s, std::string* row) {
  const OptimizerCounters& o = s.optimizer;
  Col(row, std::string(ToString(o.tracking)));
  Col(row, o.processed);
  Col(row, o.last_update_ms);
  Col(row, o.max_update_ms);
  Col(row, o.degenerate_directions);
  Col(row, o.reinitializations);
  Col(row, o.skipped_behind);
  Col(row, o.imu_only_s);
  Col(row, o.map_points);
  Col(row, s.loop_closure.nodes);
  Col(row, s.loop_closure.accepted);
  Col(row, s.loop_closure.rejected);
  Col(row, s.loop_closure.correction_m);
  const LocalizationCounters& l = s.localization;
  Col(row, l.enabled ? std::string(estimator::ToString(l.state)) : std::string());
  Col(row, l.tracked);
  Col(row, l.lost);
  Col(row, l.hints);
}

/// The LiDAR–IMU time offset applied to the IMU samples, its σ (empty before the estimator has
/// rows), the moving points taken out of the maps and the operator's resets (both cumulative).
void TimeOffsetColumns(const HealthSnapshot& s, std::string* row) {
  const estimator::TimeOffsetStatus& t = s.optimizer.time_offset;
  Col(row, t.offset_s * 1e3);
  if (t.sigma_s < 0.0) {
    Col(row, std::string());
  } else {
    Col(row, t.sigma_s * 1e3);
  }
  Col(row, s.optimizer.dynamic_removed);
  Col(row, s.optimizer.operator_resets);
}

}  // namespace

std::string HealthCsvRow(const HealthSnapshot& s,
                         int64_t t_ns,
                         int64_t realtime_ns,
                         const ProcessUsage& usage) {
  std::string row = std::to_string(t_ns);
  Col(&row, UtcIso(realtime_ns));
  SensorColumns(s, &row);
  EstimatorColumns(s, &row);
  Col(&row, s.propagator.poses);
  Col(&row, QueueMaxFill(s));
  Col(&row, TotalDrops(s));
  Col(&row, s.stamp_clock.steps);
  char cpu[32];
  std::snprintf(cpu, sizeof cpu, "%.3f", usage.cpu_s);
  Col(&row, std::string(cpu));
  Col(&row, usage.rss_mb);
  TimeOffsetColumns(s, &row);
  return row;
}

}  // namespace swlio::daemon

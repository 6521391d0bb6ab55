#include "swlio/daemon/runtime/health.h"

#include <cstdio>
#include <numbers>
#include <optional>

namespace swlio::daemon {
namespace {

std::string Num(double v, const char* format = "%.3f") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string Count(uint64_t v) { return std::to_string(v); }

/// A counter's increase; 0 when it went down (a restarted thread's counters).
uint64_t Since(uint64_t now, uint64_t before) { return now > before ? now - before : 0; }

double PerSecond(uint64_t now, uint64_t before, double dt_s) {
  return dt_s > 0.0 && now >= before ? static_cast<double>(now - before) / dt_s : 0.0;
}

ipc::DiagnosticStatus LidarStatus(const HealthSnapshot& s, const HealthRates& r) {
  ipc::DiagnosticStatus d;
  d.name = "swlio: lidar";
  d.hardware_id = "rs16";
  const LidarStageCounters& l = s.optimizer.lidar;
  const bool streaming = r.lidar_packets_hz > 0.0;
  d.level = streaming ? ipc::DiagnosticLevel::kOk : ipc::DiagnosticLevel::kError;
  d.message = streaming ? "streaming" : "no packets";
  if (streaming && r.lidar_clock_jumps > 0) {
    d.level = ipc::DiagnosticLevel::kWarn;
    d.message = "streaming; clock jumped";
  }
  d.values = {{"packets_hz", Num(r.lidar_packets_hz, "%.1f")},
              {"sweeps_hz", Num(r.sweeps_hz, "%.2f")},
              {"datagrams", Count(s.lidar_rx.datagrams)},
              {"truncated", Count(s.lidar_rx.truncated)},
              {"rx_errors", Count(s.lidar_rx.errors)},
              {"bad_packets", Count(l.bad_packets)},
              {"difop_packets", Count(l.info_packets)},
              {"difop_errors", Count(l.info_errors)},
              {"missing_packets", Count(l.missing_packets)},
              {"partial_sweeps", Count(l.partial_sweeps)},
              {"clock_offset_s", Num(s.optimizer.lidar_clock.offset_ns * 1e-9, "%.6f")},
              {"clock_drift_ppm", Num(s.optimizer.lidar_clock.drift_ppm, "%.2f")},
              {"clock_jumps", Count(s.optimizer.lidar_clock.jumps)},
              {"read_lag_ms_p50", Num(r.lidar_read_lag.p50_ms, "%.2f")},
              {"read_lag_ms_p99", Num(r.lidar_read_lag.p99_ms, "%.2f")},
              {"read_lag_ms_max", Num(r.lidar_read_lag.max_ms, "%.2f")}};
  return d;
}

ipc::DiagnosticStatus ImuStatus(const HealthSnapshot& s, const HealthRates& r) {
  ipc::DiagnosticStatus d;
  d.name = "swlio: imu";
  d.hardware_id = "xsens-mti";
  const bool streaming = r.imu_hz > 0.0;
  d.level = streaming ? ipc::DiagnosticLevel::kOk : ipc::DiagnosticLevel::kError;
  d.message = streaming ? "streaming" : (s.imu_rx.opens == 0 ? "device not open" : "no samples");
  if (streaming && r.imu_clock_jumps > 0) {
    d.level = ipc::DiagnosticLevel::kWarn;
    d.message = "streaming; clock jumped";
  }
  d.values = {{"rate_hz", Num(r.imu_hz, "%.1f")},
              {"samples", Count(s.propagator.decode.samples)},
              {"checksum_errors", Count(ImuChecksumErrors(s))},
              {"skipped_bytes", Count(ImuSkippedBytes(s))},
              {"missing_packets", Count(s.propagator.decode.missing_packets)},
              {"dropped_samples", Count(s.propagator.dropped)},
              {"invalid_samples", Count(s.propagator.invalid)},
              {"disconnects", Count(s.imu_rx.disconnects)},
              {"configurations", Count(s.imu_rx.configurations)},
              {"config_failures", Count(s.imu_rx.config_failures)},
              {"clock_offset_s", Num(s.propagator.clock_offset_ns * 1e-9, "%.6f")},
              {"clock_drift_ppm", Num(s.propagator.clock_drift_ppm, "%.2f")},
              {"clock_jumps", Count(s.propagator.clock_jumps)},
              {"read_lag_ms_p50", Num(r.imu_read_lag.p50_ms, "%.2f")},
              {"read_lag_ms_p99", Num(r.imu_read_lag.p99_ms, "%.2f")},
              {"read_lag_ms_max", Num(r.imu_read_lag.max_ms, "%.2f")}};
  return d;
}

ipc::DiagnosticStatus CanStatus(const HealthSnapshot& s, const HealthRates& r) {
  ipc::DiagnosticStatus d;
  d.name = "swlio: can";
  d.hardware_id = "socketcan";
  const bool streaming = r.can_frames_hz > 0.0;
  d.level =
      streaming && !s.can_rx.closed ? ipc::DiagnosticLevel::kOk : ipc::DiagnosticLevel::kError;
  d.message = s.can_rx.closed ? "interface closed" : streaming ? "streaming" : "no frames";
  d.values = {{"frames_hz", Num(r.can_frames_hz, "%.1f")},
              {"frames", Count(s.can_rx.frames)},
              {"odometry_samples", Count(s.can_rx.odometry_samples)},
              {"unknown_id", Count(s.can_rx.unknown_id)},
              {"bad_frames", Count(s.can_rx.bad_frames)},
              {"read_errors", Count(s.can_rx.read_errors)}};
  return d;
}

ipc::DiagnosticStatus LoopClosureStatus(const HealthSnapshot& s) {
  const LoopClosureCounters& c = s.loop_closure;
  ipc::DiagnosticStatus d;
  d.name = "swlio: loop closure";
  d.hardware_id = "swlio";
  d.level = ipc::DiagnosticLevel::kOk;
  d.message =
      std::to_string(c.accepted) + " loops closed over " + std::to_string(c.nodes) + " graph nodes";
  d.values = {{"keyframes", Count(c.keyframes)},
              {"nodes", Count(c.nodes)},
              {"attempts", Count(c.attempts)},
              {"accepted", Count(c.accepted)},
              {"rejected", Count(c.rejected)},
              {"loops_switched_off", Count(c.loops_switched_off)},
              {"attempt_ms", Num(c.last_attempt_ms, "%.1f")},
              {"attempt_ms_max", Num(c.max_attempt_ms, "%.1f")},
              {"correction_m", Num(c.correction_m, "%.3f")},
              {"correction_deg", Num(c.correction_rad * 180.0 / std::numbers::pi, "%.3f")}};
  if (c.gnss) {
    d.values.push_back({"gnss_fixes", Count(c.gnss_fixes)});
    d.values.push_back({"gnss_edges", Count(c.gnss_edges)});
    d.values.push_back({"gnss_rejected", Count(c.gnss_rejected)});
    d.values.push_back({"gnss_switched_off", Count(c.gnss_switched_off)});
    d.values.push_back({"gnss_aligned", c.gnss_aligned ? "true" : "false"});
    d.values.push_back({"enu_yaw_deg", Num(c.enu_yaw_rad * 180.0 / std::numbers::pi, "%.2f")});
  }
  if (c.hints > 0) {
    d.values.push_back({"hints", Count(c.hints)});
    d.values.push_back({"hints_refused", Count(c.hints_refused)});
    d.values.push_back({"last_hint", c.last_hint});
  }
  return d;
}

/// A refused pose hint is news for this long: the status warns with its reason.
constexpr int64_t kHintNewsNs = 30'000'000'000;

/// Warn until the pose is localized in the saved map (nothing is published before), while a
/// localization is being confirmed or was lost, and for 30 s after an operator's hint was
/// refused (with the reason).
ipc::DiagnosticStatus LocalizationStatus(const HealthSnapshot& s) {
  const LocalizationCounters& c = s.localization;
  ipc::DiagnosticStatus d;
  d.name = "swlio: localization";
  d.hardware_id = "swlio";
  const bool tracking = c.state == estimator::LocalizationState::kTracking;
  d.level = tracking ? ipc::DiagnosticLevel::kOk : ipc::DiagnosticLevel::kWarn;
  d.message = tracking               ? "localized in the saved map"
              : c.localized_t_ns < 0 ? "not localized yet: relocalizing, no pose published"
                                     : "localization lost: following odometry, relocalizing";
  d.values = {{"state", estimator::ToString(c.state)},
              {"map_nodes", Count(c.map_nodes)},
              {"keyframes", Count(c.keyframes)},
              {"hypotheses", Count(c.hypotheses)},
              {"hypotheses_dropped", Count(c.hypotheses_dropped)},
              {"tracked", Count(c.tracked)},
              {"track_failures", Count(c.track_failures)},
              {"lost", Count(c.lost)},
              {"registration_ms", Num(c.last_ms, "%.1f")},
              {"registration_ms_max", Num(c.max_ms, "%.1f")},
              {"held_poses", Count(s.publisher.held)},
              {"hints", Count(c.hints)},
              {"hints_refused", Count(c.hints_refused)},
              {"hints_unreadable", Count(c.hints_unreadable)},
              {"last_hint", c.last_hint.empty() ? "none" : c.last_hint}};
  if (c.last_hint_refused && s.t_ns - c.last_hint_t_ns < kHintNewsNs) {
    d.level = ipc::DiagnosticLevel::kWarn;
    d.message = "pose hint " + c.last_hint + (tracking ? "; still localized as before" : "");
  }
  return d;
}

/// The current sweep on DDS (sweep_publisher.h): how many, what the last one cost the optimizer.
ipc::DiagnosticStatus SweepStatus(const HealthSnapshot& s) {
  const SweepPublishCounters& c = s.sweeps;
  ipc::DiagnosticStatus d;
  d.name = "swlio: sweep cloud";
  d.hardware_id = "swlio";
  d.level = ipc::DiagnosticLevel::kOk;
  d.message = Count(c.published) + " sweeps published";
  d.values = {{"published", Count(c.published)},
              {"failures", Count(c.failures)},
              {"held", Count(c.held)},
              {"last_ms", Num(c.last_ms, "%.2f")}};
  return d;
}

/// The map cloud on DDS: how many, how large, what they cost (map_publisher.h). Warns while
/// the newest map could not be built or written.
ipc::DiagnosticStatus MapStatus(const HealthSnapshot& s) {
  const MapPublishCounters& c = s.map;
  ipc::DiagnosticStatus d;
  d.name = "swlio: map";
  d.hardware_id = "swlio";
  d.level = c.last_failed ? ipc::DiagnosticLevel::kWarn : ipc::DiagnosticLevel::kOk;
  d.message = c.last_failed     ? "the newest map cloud was not published"
              : c.published > 0 ? std::to_string(c.points) + " points published"
                                : "no map cloud yet";
  d.values = {{"maps_published", Count(c.published)},
              {"failures", Count(c.failures)},
              {"points", Count(c.points)},
              {"bytes", Count(c.bytes)},
              {"voxel_m", Num(c.voxel_m, "%.3f")},
              {"build_ms", Num(c.build_ms, "%.1f")},
              {"write_ms", Num(c.write_ms, "%.1f")}};
  return d;
}

/// How long ago (host seconds) the last processed sweep ended: the estimate's latency plus
/// any backlog; it grows when the estimator falls behind its input or the LiDAR stops.
std::string SweepAge(const HealthSnapshot& s) {
  if (s.optimizer.last_sweep_end_host_ns == 0) return "none";
  return Num(static_cast<double>(s.t_ns - s.optimizer.last_sweep_end_host_ns) * 1e-9, "%.2f");
}

ipc::DiagnosticStatus EstimatorStatus(const HealthSnapshot& s, const HealthRates& r) {
  ipc::DiagnosticStatus d;
  d.name = "swlio: estimator";
  d.hardware_id = "swlio";
  const TrackingState t = s.optimizer.tracking;
  d.level = t == TrackingState::kTracking       ? ipc::DiagnosticLevel::kOk
            : t == TrackingState::kInitializing ? ipc::DiagnosticLevel::kWarn
            : t == TrackingState::kDegraded     ? ipc::DiagnosticLevel::kWarn
                                                : ipc::DiagnosticLevel::kError;
  d.message = ToString(t);
  if (s.optimizer.recovering)
    d.message += std::string(": re-initializing after ") + s.optimizer.last_divergence;
  if (s.optimizer.imu_only_s > 0.0)
    d.message += ": no LiDAR sweeps, IMU only for " + Num(s.optimizer.imu_only_s, "%.1f") + " s";
  if (r.sweeps_skipped_behind > 0) {  // the IMU-rate pose still flows; sweeps are shed
    if (d.level == ipc::DiagnosticLevel::kOk) d.level = ipc::DiagnosticLevel::kWarn;
    d.message += "; degraded: CPU (" + Count(r.sweeps_skipped_behind) +
                 " sweeps skipped, the estimator fell behind)";
  }
  d.values = {
      {"state", ToString(t)},
      {"sweeps", Count(s.optimizer.processed)},
      {"degenerate_directions", Count(static_cast<uint64_t>(s.optimizer.degenerate_directions))},
      {"solve_ms", Num(s.optimizer.last_update_ms, "%.2f")},
      {"solve_ms_max", Num(s.optimizer.max_update_ms, "%.2f")},
      {"pose_rate_hz", Num(r.poses_hz, "%.1f")},
      {"poses_coalesced", Count(s.propagator.poses_coalesced)},
      {"pose_latency_ms_p50", Num(r.pose_latency.p50_ms, "%.2f")},
      {"pose_latency_ms_p99", Num(r.pose_latency.p99_ms, "%.2f")},
      {"pose_latency_ms_max", Num(r.pose_latency.max_ms, "%.2f")},
      {"sweeps_without_imu_dropped", Count(s.optimizer.dropped_waiting)},
      {"sweeps_skipped_behind", Count(s.optimizer.skipped_behind)},
      {"local_map_points", Count(s.optimizer.map_points)},
      {"reinitializations", Count(s.optimizer.reinitializations)},
      {"operator_resets", Count(s.optimizer.operator_resets)},
      {"imu_only_s", Num(s.optimizer.imu_only_s, "%.2f")},
      {"sweep_age_s", SweepAge(s)},
      {"last_divergence", s.optimizer.last_divergence},
      {"standing_still", s.optimizer.standing_still ? "true" : "false"},
      {"standstill_sweeps", Count(s.optimizer.standstill_sweeps)},
      {"imu_time_offset_ms", Num(s.optimizer.time_offset.offset_s * 1e3, "%.2f")},
      {"imu_time_offset_estimate_ms", Num(s.optimizer.time_offset.estimate_s * 1e3, "%.2f")},
      {"imu_time_offset_sigma_ms", s.optimizer.time_offset.sigma_s < 0.0
                                       ? "unknown"
                                       : Num(s.optimizer.time_offset.sigma_s * 1e3, "%.2f")},
      {"imu_time_offset_updates", Count(s.optimizer.time_offset.updates)},
      {"moving_points_removed", Count(s.optimizer.dynamic_removed)}};
  if (const std::optional<double>& w = s.optimizer.time_offset.window_offset_s) {
    d.values.push_back({"imu_time_offset_window_ms", Num(*w * 1e3, "%.2f")});
  }
  if (s.optimizer.wheel_factors + s.optimizer.wheel_rejected > 0) {
    d.values.push_back({"wheel_factors", Count(s.optimizer.wheel_factors)});
    d.values.push_back({"wheel_rejected", Count(s.optimizer.wheel_rejected)});
  }
  return d;
}

/// The published stamps' clock (stamp_clock.h): which one, its offset from the daemon's
/// monotonic time, and the wall clock's steps (a warning for the report after each).
ipc::DiagnosticStatus TimeStatus(const HealthSnapshot& s, const HealthRates& r) {
  const StampClockCounters& c = s.stamp_clock;
  ipc::DiagnosticStatus d;
  d.name = "swlio: time";
  d.hardware_id = "swlio";
  d.level = r.wall_clock_steps > 0 ? ipc::DiagnosticLevel::kWarn : ipc::DiagnosticLevel::kOk;
  d.message = c.realtime ? "stamps on CLOCK_REALTIME" : "stamps on CLOCK_MONOTONIC";
  if (r.wall_clock_steps > 0) {
    d.message += "; wall clock stepped by " +
                 Num(static_cast<double>(c.last_step_ns) * 1e-9, "%+.6f") + " s";
  }
  d.values = {{"stamp_clock", c.realtime ? "realtime" : "monotonic"},
              {"realtime_minus_monotonic_s", Num(static_cast<double>(c.offset_ns) * 1e-9, "%.6f")},
              {"wall_clock_steps", Count(c.steps)},
              {"last_step_s", Num(static_cast<double>(c.last_step_ns) * 1e-9, "%+.6f")}};
  return d;
}

ipc::DiagnosticStatus QueueStatus(const HealthSnapshot& s) {
  ipc::DiagnosticStatus d;
  d.name = "swlio: queues";
  d.hardware_id = "swlio";
  uint64_t drops = s.publisher.non_finite;
  for (const QueueCounters& q : s.queues) {
    drops += q.dropped;
    d.values.push_back({q.name + " (" + q.producer + "->" + q.consumer + ")",
                        "depth " + std::to_string(q.depth) + "/" + std::to_string(q.capacity) +
                            ", high " + std::to_string(q.high_water) + ", dropped " +
                            std::to_string(q.dropped)});
  }
  // What the publisher thread wrote (the map cloud and the sweep have their own statuses).
  d.values.push_back({"dds_samples", "poses " + Count(s.publisher.poses) + ", tf " +
                                         Count(s.publisher.transforms) + ", odometry " +
                                         Count(s.publisher.odometry) + ", odom_odometry " +
                                         Count(s.publisher.odom_odometry) + ", paths " +
                                         Count(s.publisher.paths) + ", tf_static re-sent " +
                                         Count(s.publisher.static_resends)});
  d.values.push_back({"dds_write_failures", Count(s.publisher.failures)});
  d.values.push_back({"non_finite_poses_dropped", Count(s.publisher.non_finite)});
  d.level = drops == 0 ? ipc::DiagnosticLevel::kOk : ipc::DiagnosticLevel::kWarn;
  d.message = drops == 0 ? "no drops" : std::to_string(drops) + " dropped";
  return d;
}

}  // namespace

const char* ToString(TrackingState state) {
  switch (state) {
    case TrackingState::kInitializing:
      return "initializing";
    case TrackingState::kTracking:
      return "tracking";
    case TrackingState::kDegraded:
      return "degraded";
    case TrackingState::kLost:
      return "lost";
  }
  return "unknown";
}

HealthRates HealthReporter::Rates(const HealthSnapshot& now) {
  HealthRates r;
  if (have_previous_) {
    const double dt = static_cast<double>(now.t_ns - previous_.t_ns) * 1e-9;
    r.lidar_packets_hz =
        PerSecond(now.optimizer.lidar.data_packets, previous_.optimizer.lidar.data_packets, dt);
    r.sweeps_hz = PerSecond(now.optimizer.lidar.sweeps, previous_.optimizer.lidar.sweeps, dt);
    r.imu_hz = PerSecond(now.propagator.samples, previous_.propagator.samples, dt);
    r.poses_hz = PerSecond(now.publisher.poses, previous_.publisher.poses, dt);
    r.can_frames_hz = PerSecond(now.can_rx.frames, previous_.can_rx.frames, dt);
  }
  const HealthSnapshot& before = have_previous_ ? previous_ : HealthSnapshot{};
  r.lidar_clock_jumps = Since(now.optimizer.lidar_clock.jumps, before.optimizer.lidar_clock.jumps);
  r.imu_clock_jumps = Since(now.propagator.clock_jumps, before.propagator.clock_jumps);
  r.wall_clock_steps = Since(now.stamp_clock.steps, before.stamp_clock.steps);
  r.sweeps_skipped_behind = Since(now.optimizer.skipped_behind, before.optimizer.skipped_behind);
  r.imu_read_lag = Summarize(now.propagator.read_lag, before.propagator.read_lag);
  r.lidar_read_lag = Summarize(now.lidar_rx.read_lag, before.lidar_rx.read_lag);
  r.pose_latency = Summarize(now.publisher.pose_latency, before.publisher.pose_latency);
  previous_ = now;
  have_previous_ = true;
  return r;
}

ipc::DiagnosticArray HealthReporter::Diagnostics(const HealthSnapshot& now) {
  const HealthRates r = Rates(now);
  ipc::DiagnosticArray a;
  a.t_ns = now.t_ns;
  a.status = {LidarStatus(now, r), ImuStatus(now, r), EstimatorStatus(now, r), QueueStatus(now),
              TimeStatus(now, r)};
  if (now.can_enabled) a.status.push_back(CanStatus(now, r));
  if (now.loop_closure.enabled) a.status.push_back(LoopClosureStatus(now));
  if (now.localization.enabled) a.status.push_back(LocalizationStatus(now));
  if (now.map.enabled) a.status.push_back(MapStatus(now));
  if (now.sweeps.enabled) a.status.push_back(SweepStatus(now));
  if (now.recording) a.status.push_back(RecorderStatus(now));
  return a;
}

std::string HealthReporter::StatusLine(const HealthSnapshot& now) {
  return ::swlio::daemon::StatusLine(now, Rates(now));
}

std::string StatusLine(const HealthSnapshot& now, const HealthRates& r) {
  char line[512];
  std::snprintf(line, sizeof line,
                "status %s | lidar %.0f pkt/s %.1f sweeps/s, missing %llu | imu %.0f Hz, "
                "checksum errors %llu, gaps %llu | pose %.0f Hz | update %.1f ms (max %.1f) | "
                "drops %llu | skipped behind %llu | reinit %llu (operator resets %llu) | "
                "clock jumps lidar %llu imu %llu | "
                "lag p99 imu read %.1f ms, lidar read %.1f ms, read to pose %.1f ms",
                ToString(now.optimizer.tracking), r.lidar_packets_hz, r.sweeps_hz,
                static_cast<unsigned long long>(now.optimizer.lidar.missing_packets), r.imu_hz,
                static_cast<unsigned long long>(ImuChecksumErrors(now)),
                static_cast<unsigned long long>(now.propagator.decode.missing_packets), r.poses_hz,
                now.optimizer.last_update_ms, now.optimizer.max_update_ms,
                static_cast<unsigned long long>(TotalDrops(now)),
                static_cast<unsigned long long>(now.optimizer.skipped_behind),
                static_cast<unsigned long long>(now.optimizer.reinitializations),
                static_cast<unsigned long long>(now.optimizer.operator_resets),
                static_cast<unsigned long long>(now.optimizer.lidar_clock.jumps),
                static_cast<unsigned long long>(now.propagator.clock_jumps), r.imu_read_lag.p99_ms,
                r.lidar_read_lag.p99_ms, r.pose_latency.p99_ms);
  return line;
}

uint64_t ImuChecksumErrors(const HealthSnapshot& s) {
  return s.imu_rx.checksum_errors + s.propagator.decode.checksum_errors;
}

uint64_t ImuSkippedBytes(const HealthSnapshot& s) {
  return s.imu_rx.skipped_bytes + s.propagator.decode.skipped_bytes;
}

uint64_t TotalDrops(const HealthSnapshot& s) {
  uint64_t drops = s.lidar_rx.truncated + s.optimizer.dropped_waiting + s.publisher.non_finite;
  for (const QueueCounters& q : s.queues) drops += q.dropped;
  return drops;
}

std::vector<std::string> ClockJumpWarnings(const HealthSnapshot& now, const HealthRates& rates) {
  std::vector<std::string> out;
  auto add = [&out](const char* sensor, uint64_t jumps, uint64_t total, double offset_ns,
                    double drift_ppm, const char* cause) {
    if (jumps == 0) return;
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s clock: jumped %llu time(s) since the last status (%llu in all); offset "
                  "now %.6f s, drift %.1f ppm. The sensor's time was stepped (%s) or does not "
                  "run at the host's rate; data across a jump is mis-timed",
                  sensor, static_cast<unsigned long long>(jumps),
                  static_cast<unsigned long long>(total), offset_ns * 1e-9, drift_ppm, cause);
    out.emplace_back(line);
  };
  const drivers::ClockModelStats& lidar = now.optimizer.lidar_clock;
  add("lidar", rates.lidar_clock_jumps, lidar.jumps, lidar.offset_ns, lidar.drift_ppm,
      "GPS/PTP time arriving, a reset");
  add("imu", rates.imu_clock_jumps, now.propagator.clock_jumps, now.propagator.clock_offset_ns,
      now.propagator.clock_drift_ppm, "a device reset or reconfiguration");
  return out;
}

}  // namespace swlio::daemon

#include "swlio/daemon/blackbox/incident_detector.h"

#include <algorithm>

#include "swlio/estimator/map/map_localizer.h"

namespace swlio::daemon {
namespace {

uint64_t Since(uint64_t now, uint64_t before) { return now > before ? now - before : 0; }

std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

uint64_t PipelineDrops(const HealthSnapshot& s) {
  uint64_t drops = s.publisher.non_finite;
  for (const QueueCounters& q : s.queues) {
    if (q.consumer != "recorder") drops += q.dropped;
  }
  return drops;
}

std::vector<IncidentEvent> IncidentDetector::Update(const HealthSnapshot& s,
                                                    int64_t t_ns,
                                                    int64_t realtime_ns,
                                                    const std::vector<std::string>& stalled) {
  out_.clear();
  t_ns_ = t_ns;
  realtime_ns_ = realtime_ns;
  CheckSilence(&lidar_, s.lidar_rx.datagrams, "lidar_silent", "LiDAR datagram");
  CheckSilence(&imu_, s.propagator.samples, "imu_silent", "IMU sample");
  if (have_previous_) {
    CheckSensors(s, previous_);
    CheckEstimator(s, previous_);
    CheckLocalization(s, previous_);
  }
  if (!stalled.empty() && !watchdog_stalled_) {
    Emit("watchdog", "threads not progressing: " + Join(stalled));
  }
  watchdog_stalled_ = !stalled.empty();
  previous_ = s;
  have_previous_ = true;
  return out_;
}

void IncidentDetector::Emit(const std::string& reason, std::string detail) {
  auto it = last_emitted_ns_.find(reason);
  if (it != last_emitted_ns_.end() && t_ns_ - it->second < kRepeatNs) return;
  last_emitted_ns_[reason] = t_ns_;
  out_.push_back({t_ns_, realtime_ns_, reason, std::move(detail)});
}

void IncidentDetector::CheckSilence(Silence* s,
                                    uint64_t count,
                                    const char* reason,
                                    const char* sensor) {
  if (count != s->last_count || !s->seen) {
    if (count != s->last_count) {
      s->seen = s->seen || count > 0;
      s->silent = false;
    }
    s->last_count = count;
    s->last_change_ns = t_ns_;
    return;
  }
  if (!s->silent && t_ns_ - s->last_change_ns >= kSilentNs) {
    s->silent = true;
    Emit(reason, std::string("no ") + sensor + " for " +
                     std::to_string((t_ns_ - s->last_change_ns) / 1'000'000) + " ms");
  }
}

void IncidentDetector::CheckSensors(const HealthSnapshot& now, const HealthSnapshot& before) {
  const LidarStageCounters& a = now.optimizer.lidar;
  const LidarStageCounters& b = before.optimizer.lidar;
  const uint64_t lost =
      Since(a.missing_packets, b.missing_packets) + Since(a.bad_packets, b.bad_packets);
  const uint64_t packets = Since(now.lidar_rx.datagrams, before.lidar_rx.datagrams);
  if (lost >= kLossyMinPackets &&
      static_cast<double>(lost) >= kLossyFraction * static_cast<double>(packets + lost)) {
    Emit("lidar_lossy", std::to_string(lost) + " LiDAR packets missing or bad of " +
                            std::to_string(packets + lost));
  }
  const uint64_t unplugs = Since(now.imu_rx.disconnects, before.imu_rx.disconnects);
  if (unplugs > 0) Emit("imu_silent", "the IMU's serial device went away");
  const uint64_t bad = Since(ImuChecksumErrors(now), ImuChecksumErrors(before)) +
                       Since(now.propagator.invalid, before.propagator.invalid);
  if (bad > 0) Emit("imu_lossy", std::to_string(bad) + " IMU frames with bad checksums or values");
  const uint64_t jumps =
      Since(now.optimizer.lidar_clock.jumps, before.optimizer.lidar_clock.jumps) +
      Since(now.propagator.clock_jumps, before.propagator.clock_jumps) +
      Since(now.stamp_clock.steps, before.stamp_clock.steps);
  if (jumps > 0) {
    Emit("clock_jump", std::to_string(jumps) + " clock jump(s): LiDAR " +
                           std::to_string(now.optimizer.lidar_clock.jumps) + ", IMU " +
                           std::to_string(now.propagator.clock_jumps) + ", wall clock " +
                           std::to_string(now.stamp_clock.steps) + " in all");
  }
  const uint64_t drops = Since(PipelineDrops(now), PipelineDrops(before));
  if (drops > 0) Emit("queue_drops", std::to_string(drops) + " samples dropped by full queues");
}

void IncidentDetector::CheckEstimator(const HealthSnapshot& now, const HealthSnapshot& before) {
  const OptimizerCounters& a = now.optimizer;
  const OptimizerCounters& b = before.optimizer;
  // An operator's reset (swlioctl reset) is no incident: the control log says who asked.
  if (a.reinitializations - a.operator_resets > b.reinitializations - b.operator_resets) {
    Emit("divergence",
         std::string("the estimator diverged (") + a.last_divergence + ") and re-initialized");
  }
  const uint64_t skipped = Since(a.skipped_behind, b.skipped_behind);
  if (skipped > 0) {
    Emit("estimator_behind",
         std::to_string(skipped) + " sweeps skipped: the estimator fell behind");
  }
}

void IncidentDetector::CheckLocalization(const HealthSnapshot& now, const HealthSnapshot& before) {
  const LocalizationCounters& l = now.localization;
  if (!l.enabled) return;
  if (l.lost > before.localization.lost) Emit("localization_lost", "lost the saved map");
  const bool confirming = l.state == estimator::LocalizationState::kConfirming;
  if (!confirming) {
    confirming_since_ns_ = -1;
    ambiguous_ = false;
    return;
  }
  if (confirming_since_ns_ < 0) confirming_since_ns_ = t_ns_;
  if (!ambiguous_ && t_ns_ - confirming_since_ns_ >= kAmbiguousNs) {
    ambiguous_ = true;
    Emit("localization_ambiguous",
         std::to_string(l.hypotheses) + " places fit; none confirmed for " +
             std::to_string((t_ns_ - confirming_since_ns_) / 1'000'000'000) + " s");
  }
}

}  // namespace swlio::daemon

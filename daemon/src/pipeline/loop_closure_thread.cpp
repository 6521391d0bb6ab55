#include "swlio/daemon/pipeline/loop_closure_thread.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <numbers>

#include "swlio/core/time.h"
#include "swlio/estimator/map/map_pcd.h"

namespace swlio::daemon {

LoopClosureThread::LoopClosureThread(const estimator::LoopClosureConfig& config,
                                     const LoopClosureQueues& queues)
    : closure_(config), q_(queues), gnss_(config.gnss.enabled) {}

void LoopClosureThread::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  KeyframePtr keyframe;
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    ServeSaves(beat);
    PublishMapIfDue(beat);  // also when idle: a correction may wait for the period to end
    DrainGnss();            // 4 Hz at most: the keyframe wait below is short enough
    hints_.Drain([this](const PoseHint& h) { ApplyHint(h); });
    if (!q_.keyframes_in->WaitPop(&keyframe, 100'000)) continue;
    Handle(*keyframe);
    newest_ = keyframe;  // a copy: WaitPop assigns `keyframe` next
    keyframe.reset();
  }
  hints_.FailQueued();
  // Stopping: the optimizer has stopped; what it queued last is not worth a solve now.
}

void LoopClosureThread::Handle(const estimator::KeyframeCloud& keyframe) {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  keyframes_.fetch_add(1, kRelaxed);
  const int64_t t0 = MonotonicNowNs();
  const size_t nodes_before = closure_.stats().nodes;
  const estimator::LoopClosureUpdate u = closure_.AddKeyframe(keyframe);
  const estimator::LoopClosureStats& st = closure_.stats();
  nodes_.store(st.nodes, kRelaxed);
  // The map grew: publish it (at most once per period), so a viewer sees the area being
  // mapped, not only what the last correction covered.
  if (map_ != nullptr && st.nodes > nodes_before) map_->MarkChanged();
  const double ms = static_cast<double>(MonotonicNowNs() - t0) * 1e-6;
  if (u.attempted) {
    last_ms_.store(ms, kRelaxed);
    max_ms_.store(std::max(max_ms_.load(kRelaxed), ms), kRelaxed);
    attempts_.store(st.attempts, kRelaxed);
    accepted_.store(st.accepted, kRelaxed);
    rejected_.store(st.rejected, kRelaxed);
  }
  if (gnss_) PublishGnssCounters();
  if (!u.optimized) return;
  ApplyCorrection(u, keyframe.t_ns);
  if (!u.attempted) return;                                  // solved for new GNSS edges
  const double correction_m = correction_m_.load(kRelaxed);  // as ApplyCorrection stored it
  const double correction_rad = correction_rad_.load(kRelaxed);
  spdlog::info(
      "loop closure: node {} matches node {} ({:.2f} m apart, fitness {:.2f}); graph of {} "
      "nodes solved in {:.1f} ms, correction now {:.2f} m / {:.2f} deg",
      u.attempt.node, u.attempt.candidate, u.attempt.distance_m, u.attempt.check.fitness, st.nodes,
      ms, correction_m, correction_rad * 180.0 / std::numbers::pi);
}

void LoopClosureThread::ApplyCorrection(const estimator::LoopClosureUpdate& u, int64_t t_ns) {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  switched_off_.fetch_add(u.summary.loops_switched_off, kRelaxed);
  const Eigen::Isometry3d C = closure_.T_map_odom();
  correction_m_.store(C.translation().norm(), kRelaxed);
  correction_rad_.store(Eigen::AngleAxisd(C.rotation()).angle(), kRelaxed);
  if (map_ != nullptr) map_->MarkChanged();
  q_.corrections_out->Push(MapCorrection{
      t_ns, C, std::make_shared<const std::vector<estimator::MapNode>>(closure_.MapPath())});
}

void LoopClosureThread::ApplyHint(const PoseHint& hint) {
  std::string text;
  bool refused = true;
  if (gnss_) {
    text = "refused: the map frame is tied to ENU by GNSS (estimator.loop_closure.gnss)";
  } else if (!newest_) {
    text = "refused: no keyframe yet (the estimator has not started)";
  } else {
    // A moves the map frame so that the IMU at the newest keyframe lands on the hint's x, y,
    // yaw; its height and tilt stay.
    const estimator::LocalizationHint h = ImuHint(hint, T_base_imu_);
    const Eigen::Isometry3d T_map_imu = closure_.T_map_odom() * newest_->T_world_imu;
    const double yaw_now = std::atan2(T_map_imu.linear()(1, 0), T_map_imu.linear()(0, 0));
    Eigen::Isometry3d A = Eigen::Isometry3d::Identity();
    A.linear() = Eigen::AngleAxisd(h.yaw_rad - yaw_now, Eigen::Vector3d::UnitZ()).matrix();
    const Eigen::Vector3d moved = A.linear() * T_map_imu.translation();
    A.translation() << h.x_m - moved.x(), h.y_m - moved.y(), 0.0;
    refused = !closure_.Reanchor(A);  // false only with GNSS, refused above
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "map frame re-anchored: base_link at (%.2f, %.2f) yaw %.1f deg (moved %.2f m, "
                  "turned %.1f deg)",
                  hint.x_m, hint.y_m, hint.yaw_rad * 180.0 / std::numbers::pi,
                  A.translation().norm(),
                  Eigen::AngleAxisd(A.linear()).angle() * 180.0 / std::numbers::pi);
    text = refused ? std::string("refused: the map frame could not be moved") : std::string(buf);
  }
  {
    std::lock_guard<std::mutex> lock(hint_mutex_);
    ++hint_.hints;
    hint_.hints_refused += refused ? 1 : 0;
    hint_.last_hint = text;
  }
  if (refused) {
    spdlog::warn("loop closure: hint from {}: {}", hint.source, text);
  } else {
    spdlog::info("loop closure: hint from {}: {}", hint.source, text);
    if (map_ != nullptr) map_->MarkChanged();
    MapCorrection c{newest_->t_ns, closure_.T_map_odom(),
                    std::make_shared<const std::vector<estimator::MapNode>>(closure_.MapPath())};
    c.jump = true;  // the operator moved the frame: no slewing
    q_.corrections_out->Push(std::move(c));
  }
  if (hint.command) {
    const std::string_view prefix = "refused: ";
    hint.command->Finish(
        refused ? control::Reply{control::ReplyStatus::kRefused, text.substr(prefix.size()), {}}
                : control::Reply{control::ReplyStatus::kOk, text, {}});
  }
}

void LoopClosureThread::DrainGnss() {
  if (q_.gnss_in == nullptr) return;
  GnssFix fix;
  while (q_.gnss_in->Pop(&fix)) {
    gnss_fixes_.fetch_add(1, std::memory_order_relaxed);
    const bool aligned = closure_.T_enu_map().has_value();
    const estimator::LoopClosureUpdate u = closure_.AddGnss(fix);
    if (!aligned && closure_.T_enu_map()) {
      const Eigen::Isometry3d T = *closure_.T_enu_map();
      spdlog::info(
          "GNSS: map frame aligned to the local ENU frame (yaw {:.1f} deg, translation {:.1f} "
          "{:.1f} {:.1f} m)",
          std::atan2(T.linear()(1, 0), T.linear()(0, 0)) * 180.0 / std::numbers::pi,
          T.translation().x(), T.translation().y(), T.translation().z());
    }
    if (u.summary.gnss_switched_off > 0) {
      spdlog::warn("GNSS: {} fix(es) contradicting the odometry switched off (multipath?)",
                   u.summary.gnss_switched_off);
    }
    if (u.optimized) ApplyCorrection(u, fix.t_ns);
  }
  PublishGnssCounters();
}

void LoopClosureThread::PublishGnssCounters() {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  const estimator::LoopClosureStats& st = closure_.stats();
  gnss_edges_.store(st.gnss_edges, kRelaxed);
  gnss_switched_off_.store(st.gnss_switched_off, kRelaxed);
  gnss_rejected_.store(
      st.gnss.bad_quality + st.gnss.rate_limited + st.gnss.unplaced + st.gnss_gated, kRelaxed);
  if (const auto T = closure_.T_enu_map()) {
    gnss_aligned_.store(true, kRelaxed);
    enu_yaw_rad_.store(std::atan2(T->linear()(1, 0), T->linear()(0, 0)), kRelaxed);
  }
}

void LoopClosureThread::PublishMapIfDue(const Watchdog::Handle& beat) {
  if (map_ == nullptr || !map_->Due(MonotonicNowNs())) return;
  // Merged straight from the graph's store: a SavedMap copy of every cloud in double first
  // was the daemon's largest transient (docs/notes/2026-12-04-memory-budget.md).
  const MergeFn merge = [this](double voxel_m, const estimator::MergedCloudLimit& limit,
                               std::string* error) {
    return closure_.MergedCloud(voxel_m, error, limit);
  };
  map_->Publish(merge, closure_.map_nodes(), beat);
}

size_t LoopClosureThread::SaveMap(const std::string& path,
                                  const std::string& pcd_path,
                                  std::string* error,
                                  const Watchdog::Handle& beat) const {
  const estimator::SavedMap map = closure_.ToSavedMap();
  beat.Beat();
  if (estimator::SaveMapFile(path, map, error)) {
    beat.Beat();
    estimator::SaveMergedPcd(pcd_path, map, estimator::kMergedCloudVoxelM, error);
  }
  return map.nodes.size();
}

bool LoopClosureThread::RequestSave(std::shared_ptr<PendingCommand> command) {
  return saves_.Push(std::move(command));
}

void LoopClosureThread::ServeSaves(const Watchdog::Handle& beat) {
  std::shared_ptr<PendingCommand> command;
  while (saves_.Pop(&command)) {
    if (command->cancelled()) continue;
    const std::string& path = command->request().argument;
    if (closure_.map_nodes() == 0) {
      command->Finish({control::ReplyStatus::kRefused,
                       "no keyframes in the map yet: the estimator has not moved far enough", ""});
      continue;
    }
    const int64_t t0 = MonotonicNowNs();
    std::string error;
    const size_t nodes = SaveMap(path, path + ".pcd", &error, beat);
    if (!error.empty()) {
      command->Finish({control::ReplyStatus::kFailed, error, ""});
      continue;
    }
    char message[160];
    std::snprintf(message, sizeof message, "saved %zu nodes in %.2f s", nodes,
                  static_cast<double>(MonotonicNowNs() - t0) * 1e-9);
    std::string body = "map: ";
    body.append(path).append("\nnodes: ").append(std::to_string(nodes));
    body.append("\ncloud: ").append(path).append(".pcd\n");
    command->Finish({control::ReplyStatus::kOk, message, body});
  }
}

LoopClosureCounters LoopClosureThread::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  LoopClosureCounters c;
  c.enabled = true;
  c.keyframes = keyframes_.load(kRelaxed);
  c.nodes = nodes_.load(kRelaxed);
  c.attempts = attempts_.load(kRelaxed);
  c.accepted = accepted_.load(kRelaxed);
  c.rejected = rejected_.load(kRelaxed);
  c.loops_switched_off = switched_off_.load(kRelaxed);
  c.last_attempt_ms = last_ms_.load(kRelaxed);
  c.max_attempt_ms = max_ms_.load(kRelaxed);
  c.correction_m = correction_m_.load(kRelaxed);
  c.correction_rad = correction_rad_.load(kRelaxed);
  c.gnss = gnss_;
  c.gnss_fixes = gnss_fixes_.load(kRelaxed);
  c.gnss_edges = gnss_edges_.load(kRelaxed);
  c.gnss_switched_off = gnss_switched_off_.load(kRelaxed);
  c.gnss_rejected = gnss_rejected_.load(kRelaxed);
  c.gnss_aligned = gnss_aligned_.load(kRelaxed);
  c.enu_yaw_rad = enu_yaw_rad_.load(kRelaxed);
  std::lock_guard<std::mutex> lock(hint_mutex_);
  c.hints = hint_.hints;
  c.hints_refused = hint_.hints_refused;
  c.last_hint = hint_.last_hint;
  return c;
}

}  // namespace swlio::daemon

#include "swlio/daemon/loop_closure_thread.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <numbers>

#include "swlio/core/time.h"
#include "swlio/estimator/map_pcd.h"

namespace swlio::daemon {

LoopClosureThread::LoopClosureThread(const estimator::LoopClosureConfig& config,
                                     const LoopClosureQueues& queues)
    : closure_(config), q_(queues) {}

void LoopClosureThread::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  KeyframePtr keyframe;
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    PublishMapIfDue(beat);  // also when idle: a correction may wait for the period to end
    if (!q_.keyframes_in->WaitPop(&keyframe, 100'000)) continue;
    Handle(*keyframe);
    keyframe.reset();
  }
  // Stopping: the optimizer has stopped; what it queued last is not worth a solve now.
}

void LoopClosureThread::Handle(const estimator::KeyframeCloud& keyframe) {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  keyframes_.fetch_add(1, kRelaxed);
  const int64_t t0 = MonotonicNowNs();
  const estimator::LoopClosureUpdate u = closure_.AddKeyframe(keyframe);
  const estimator::LoopClosureStats& st = closure_.stats();
  nodes_.store(st.nodes, kRelaxed);
  if (!u.attempted) return;
  const double ms = static_cast<double>(MonotonicNowNs() - t0) * 1e-6;
  last_ms_.store(ms, kRelaxed);
  max_ms_.store(std::max(max_ms_.load(kRelaxed), ms), kRelaxed);
  attempts_.store(st.attempts, kRelaxed);
  accepted_.store(st.accepted, kRelaxed);
  rejected_.store(st.rejected, kRelaxed);
  if (!u.optimized) return;
  switched_off_.fetch_add(u.summary.loops_switched_off, kRelaxed);
  const Eigen::Isometry3d C = closure_.T_map_odom();
  const double correction_m = C.translation().norm();
  const double correction_rad = Eigen::AngleAxisd(C.rotation()).angle();
  correction_m_.store(correction_m, kRelaxed);
  correction_rad_.store(correction_rad, kRelaxed);
  if (map_ != nullptr) map_->MarkChanged();
  q_.corrections_out->Push(
      MapCorrection{keyframe.t_ns, C,
                    std::make_shared<const std::vector<estimator::MapNode>>(closure_.MapPath())});
  spdlog::info(
      "loop closure: node {} matches node {} ({:.2f} m apart, fitness {:.2f}); graph of {} "
      "nodes solved in {:.1f} ms, correction now {:.2f} m / {:.2f} deg",
      u.attempt.node, u.attempt.candidate, u.attempt.distance_m, u.attempt.check.fitness, st.nodes,
      ms, correction_m, correction_rad * 180.0 / std::numbers::pi);
}

void LoopClosureThread::PublishMapIfDue(const Watchdog::Handle& beat) {
  if (map_ == nullptr || !map_->Due(MonotonicNowNs())) return;
  const int64_t t0 = MonotonicNowNs();
  const estimator::SavedMap map = closure_.ToSavedMap();
  beat.Beat();
  map_->Publish(map, beat, static_cast<double>(MonotonicNowNs() - t0) * 1e-6);
}

size_t LoopClosureThread::SaveMap(const std::string& path,
                                  const std::string& pcd_path,
                                  std::string* error) const {
  const estimator::SavedMap map = closure_.ToSavedMap();
  if (estimator::SaveMapFile(path, map, error)) {
    estimator::SaveMergedPcd(pcd_path, map, estimator::kMergedCloudVoxelM, error);
  }
  return map.nodes.size();
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
  return c;
}

}  // namespace swlio::daemon

#include "swlio/daemon/pipeline/localization_thread.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <numbers>
#include <utility>

#include "swlio/core/time.h"
#include "swlio/daemon/runtime/event_log.h"
#include "swlio/ipc/subscriber.h"

namespace swlio::daemon {

using estimator::LocalizationState;

LocalizationThread::LocalizationThread(estimator::SavedMap map,
                                       const estimator::LocalizationConfig& config,
                                       const LoopClosureQueues& queues)
    : localizer_(std::move(map), config), q_(queues) {
  map_nodes_ = localizer_.map().nodes.size();
}

void LocalizationThread::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  beat.Beat();
  if (map_ != nullptr) map_->Publish(localizer_.map(), beat);  // keyframes wait in the queue
  KeyframePtr keyframe;
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    hints_.Drain([this](const PoseHint& h) { ApplyHint(h); });
    if (!q_.keyframes_in->WaitPop(&keyframe, 100'000)) continue;
    Handle(*keyframe);
    newest_ = keyframe;  // a copy: WaitPop assigns `keyframe` next
    keyframe.reset();
  }
  hints_.FailQueued();  // a daemon that stops answers what is still queued
}

void LocalizationThread::ApplyHint(const PoseHint& hint) {
  const int64_t t0 = MonotonicNowNs();
  estimator::HintOutcome outcome;  // kNoKeyframe until the estimator has made one
  if (newest_) outcome = localizer_.ApplyHint(*newest_, ImuHint(hint, T_base_imu_));
  const bool refused = outcome.verdict != estimator::HintVerdict::kTracking &&
                       outcome.verdict != estimator::HintVerdict::kConfirming;
  const std::string text = DescribeHint(hint, outcome);
  const double ms = static_cast<double>(MonotonicNowNs() - t0) * 1e-6;
  {
    std::lock_guard<std::mutex> lock(hint_mutex_);
    ++hint_.hints;
    hint_.hints_refused += refused ? 1 : 0;
    hint_.last_hint = text;
    hint_.last_hint_refused = refused;
    hint_.last_hint_t_ns = t0;
  }
  if (refused) {
    spdlog::warn("localization: hint from {}: {} ({} registrations, {:.0f} ms)", hint.source, text,
                 outcome.registrations, ms);
  } else {
    spdlog::info("localization: hint from {}: {} ({} registrations, {:.0f} ms)", hint.source, text,
                 outcome.registrations, ms);
  }
  if (hint.command) {
    // The reply's status says "refused" already (swlioctl prints "refused: <message>").
    const std::string_view prefix = "refused: ";
    const bool prefixed = text.compare(0, prefix.size(), prefix) == 0;
    hint.command->Finish(refused ? control::Reply{control::ReplyStatus::kRefused,
                                                  prefixed ? text.substr(prefix.size()) : text,
                                                  {}}
                                 : control::Reply{control::ReplyStatus::kOk, text, {}});
  }
  state_.store(static_cast<int>(localizer_.state()), std::memory_order_relaxed);
  hypotheses_.store(localizer_.stats().hypotheses, std::memory_order_relaxed);
  if (refused) return;
  jump_next_ = true;
  if (outcome.verdict == estimator::HintVerdict::kTracking) {
    if (localized_t_ns_.load(std::memory_order_relaxed) < 0)
      localized_t_ns_.store(newest_->t_ns, std::memory_order_relaxed);
    jump_next_ = !Publish(*newest_, true);
  }
}

void LocalizationThread::Handle(const estimator::KeyframeCloud& keyframe) {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  keyframes_.fetch_add(1, kRelaxed);
  const LocalizationState before = localizer_.state();
  const int64_t t0 = MonotonicNowNs();
  const estimator::LocalizationUpdate u = localizer_.AddKeyframe(keyframe);
  const estimator::LocalizationStats& st = localizer_.stats();
  state_.store(static_cast<int>(u.state), kRelaxed);
  hypotheses_.store(st.hypotheses, kRelaxed);
  dropped_.store(st.hypotheses_dropped, kRelaxed);
  tracked_.store(st.tracked, kRelaxed);
  failures_.store(st.track_failures, kRelaxed);
  lost_.store(st.lost, kRelaxed);
  if (u.registrations > 0) {
    const double ms = static_cast<double>(MonotonicNowNs() - t0) * 1e-6;
    last_ms_.store(ms, kRelaxed);
    max_ms_.store(std::max(max_ms_.load(kRelaxed), ms), kRelaxed);
  }
  if (before == LocalizationState::kTracking && u.state == LocalizationState::kRelocalizing) {
    LogEvent(
        spdlog::level::warn, "localization_lost",
        fmt::format("localization: lost ({} registrations in a row failed); relocalizing",
                    st.track_failures),
        {{"TRACK_FAILURES", std::to_string(st.track_failures)}, {"LOST", std::to_string(st.lost)}});
  }
  if (u.state != LocalizationState::kTracking || !u.accepted) return;
  const bool jump = !published_in_map_ || jump_next_;
  if (jump) {
    if (localized_t_ns_.load(kRelaxed) < 0) localized_t_ns_.store(keyframe.t_ns, kRelaxed);
    const Eigen::Vector3d p = (localizer_.T_map_odom() * keyframe.T_world_imu).translation();
    spdlog::info("localization: localized in the map at ({:.2f}, {:.2f}, {:.2f}) m", p.x(), p.y(),
                 p.z());
  }
  if (Publish(keyframe, jump)) jump_next_ = false;
}

bool LocalizationThread::Publish(const estimator::KeyframeCloud& keyframe, bool jump) {
  MapCorrection c;
  c.t_ns = keyframe.t_ns;
  c.T_map_odom = localizer_.T_map_odom();
  c.jump = jump;
  // A full queue means the publisher is stalled; the next correction supersedes this one, but
  // the jump must not be lost: retried with the next accepted keyframe.
  const bool pushed = q_.corrections_out->Push(std::move(c));
  published_in_map_ = pushed || published_in_map_;
  return pushed;
}

LocalizationCounters LocalizationThread::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  LocalizationCounters c;
  c.enabled = true;
  c.state = static_cast<LocalizationState>(state_.load(kRelaxed));
  c.map_nodes = map_nodes_;
  c.keyframes = keyframes_.load(kRelaxed);
  c.hypotheses = hypotheses_.load(kRelaxed);
  c.hypotheses_dropped = dropped_.load(kRelaxed);
  c.tracked = tracked_.load(kRelaxed);
  c.track_failures = failures_.load(kRelaxed);
  c.lost = lost_.load(kRelaxed);
  c.localized_t_ns = localized_t_ns_.load(kRelaxed);
  c.last_ms = last_ms_.load(kRelaxed);
  c.max_ms = max_ms_.load(kRelaxed);
  std::lock_guard<std::mutex> lock(hint_mutex_);
  c.hints = hint_.hints;
  c.hints_refused = hint_.hints_refused;
  c.hints_unreadable = hints_.unreadable();
  c.last_hint = hint_.last_hint;
  c.last_hint_refused = hint_.last_hint_refused;
  c.last_hint_t_ns = hint_.last_hint_t_ns;
  return c;
}

}  // namespace swlio::daemon

#pragma once
/// @file
/// The localization thread (issue 8; `swliod --map FILE --localize`): in place of the
/// loop-closure thread, it takes the optimizer's keyframes, runs MapLocalizer
/// (estimator/map/map_localizer.h: relocalization from place descriptors, then tracking against
/// the fixed map) and hands every new T_map_odom to the publisher. The first one jumps (the
/// publisher holds every pose until then); later ones, a relocalization after the pose was
/// lost included, are followed at the bounded rate (the planner never sees a teleport once it
/// has a pose). Shares only queues with the other threads. With a MapPublisher, the saved map's
/// cloud is published once when the thread starts (the map never changes).
/// Operator hints (pose_hint.h) come from swlioctl through RequestHint and from /initialpose
/// through a DDS reader this thread polls between keyframes (≤ 100 ms); each is applied to the
/// newest keyframe (MapLocalizer::ApplyHint), answered, logged and shown in health. An accepted
/// hint's correction jumps: the operator asked for the pose to move.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "swlio/daemon/pipeline/hint_inbox.h"
#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/loop_closure_thread.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/estimator/map/map_localizer.h"

namespace swlio::ipc {
class Subscriber;
}

namespace swlio::daemon {

struct LocalizationCounters {
  bool enabled = false;
  estimator::LocalizationState state = estimator::LocalizationState::kRelocalizing;
  uint64_t map_nodes = 0;
  uint64_t keyframes = 0;
  uint64_t hypotheses = 0;
  uint64_t hypotheses_dropped = 0;
  uint64_t tracked = 0;
  uint64_t track_failures = 0;
  uint64_t lost = 0;
  int64_t localized_t_ns = -1;  ///< daemon time of the first localization (-1: not yet)
  double last_ms = 0.0;         ///< wall time of the last keyframe's registrations
  double max_ms = 0.0;
  uint64_t hints = 0;  ///< operator hints taken (swlioctl, /initialpose)
  uint64_t hints_refused = 0;
  uint64_t hints_unreadable = 0;  ///< /initialpose messages in another frame or not a pose
  std::string last_hint;          ///< the last hint's outcome (DescribeHint); empty: none yet
  bool last_hint_refused = false;
  int64_t last_hint_t_ns = -1;  ///< daemon time it was applied
};

class LocalizationThread {
 public:
  LocalizationThread(estimator::SavedMap map,
                     const estimator::LocalizationConfig& config,
                     const LoopClosureQueues& queues);
  /// Publish the saved map's cloud through `map` (not owned; null: no map cloud) when Run
  /// starts. Call before Run.
  void PublishMapTo(MapPublisher* map) { map_ = map; }
  /// Take hints from /initialpose through `reader` (not owned; its pose topic is the hint
  /// topic), whose frame must be `map_frame`; T_base_imu turns base_link hints into the IMU's.
  /// Call before Run.
  void ReadHintsFrom(ipc::Subscriber* reader, const std::string& map_frame) {
    hints_.ReadFrom(reader, map_frame);
  }
  void SetBaseFrame(const Eigen::Isometry3d& T_base_imu) { T_base_imu_ = T_base_imu; }
  /// An operator's hint (control thread only); hint.command is answered. False when requests
  /// are already queued.
  bool RequestHint(PoseHint hint) { return hints_.Request(std::move(hint)); }
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  /// Relaxed copies (any thread).
  LocalizationCounters counters() const;

 private:
  void Handle(const estimator::KeyframeCloud& keyframe);
  /// The correction to the publisher; false when its queue was full.
  bool Publish(const estimator::KeyframeCloud& keyframe, bool jump);
  void ApplyHint(const PoseHint& hint);

  HintInbox hints_{"localization"};
  Eigen::Isometry3d T_base_imu_ = Eigen::Isometry3d::Identity();
  estimator::MapLocalizer localizer_;
  LoopClosureQueues q_;
  MapPublisher* map_ = nullptr;
  uint64_t map_nodes_ = 0;
  KeyframePtr newest_;             ///< the keyframe hints are applied to
  mutable std::mutex hint_mutex_;  ///< guards the last_hint* fields of hint_
  LocalizationCounters hint_;      ///< only the hint fields are used
  std::atomic<uint64_t> keyframes_{0}, hypotheses_{0}, dropped_{0}, tracked_{0}, failures_{0},
      lost_{0};
  std::atomic<int64_t> localized_t_ns_{-1};
  std::atomic<double> last_ms_{0.0}, max_ms_{0.0};
  std::atomic<int> state_{0};
  bool published_in_map_ = false;  ///< the jump has been sent
  bool jump_next_ = false;         ///< a hint was accepted: the next correction jumps
};

}  // namespace swlio::daemon

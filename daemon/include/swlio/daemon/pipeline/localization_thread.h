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

#include <atomic>
#include <cstdint>

#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/loop_closure_thread.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/estimator/map/map_localizer.h"

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
};

class LocalizationThread {
 public:
  LocalizationThread(estimator::SavedMap map,
                     const estimator::LocalizationConfig& config,
                     const LoopClosureQueues& queues);
  /// Publish the saved map's cloud through `map` (not owned; null: no map cloud) when Run
  /// starts. Call before Run.
  void PublishMapTo(MapPublisher* map) { map_ = map; }
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  /// Relaxed copies (any thread).
  LocalizationCounters counters() const;

 private:
  void Handle(const estimator::KeyframeCloud& keyframe);
  void Publish(const estimator::KeyframeCloud& keyframe, bool jump);

  estimator::MapLocalizer localizer_;
  LoopClosureQueues q_;
  MapPublisher* map_ = nullptr;
  uint64_t map_nodes_ = 0;
  bool published_in_map_ = false;  ///< the jump has been sent
  std::atomic<int> state_{0};
  std::atomic<uint64_t> keyframes_{0}, hypotheses_{0}, dropped_{0}, tracked_{0}, failures_{0},
      lost_{0};
  std::atomic<int64_t> localized_t_ns_{-1};
  std::atomic<double> last_ms_{0.0}, max_ms_{0.0};
};

}  // namespace swlio::daemon

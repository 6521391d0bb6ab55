#pragma once
/// @file
/// The loop-closure thread (design.md; issue 8): takes the optimizer's keyframes, runs
/// LoopClosure (estimator/loop/loop_closure.h: graph nodes, candidate verification, pose-graph
/// solves) and hands every new map correction to the publisher, which follows it at a bounded
/// rate. It never blocks the optimizer or the IMU-rate output: they share only queues, and a
/// keyframe that finds the queue full is dropped and counted (the graph then has a longer
/// odometry edge, nothing worse). With a MapPublisher, the corrected map cloud is rebuilt and
/// published here after a correction, at most once per its period (map_publisher.h).
/// GNSS (estimator.loop_closure.gnss): the propagator's fixes go into the graph too
/// (LoopClosure::AddGnss); their corrections reach the publisher the same way. With loop
/// detection off (`enabled: false`) the thread runs for GNSS alone.
/// Operators' pose hints while mapping (/initialpose, swlioctl relocalize; hint_inbox.h)
/// re-anchor the map frame: the graph moves so that base_link at the newest keyframe is where
/// the hint says (x, y, yaw; height and tilt stay), and the correction jumps there. Refused with
/// GNSS, which ties the map frame to ENU.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include "swlio/daemon/control/pending_command.h"
#include "swlio/daemon/output/map_publisher.h"
#include "swlio/daemon/pipeline/hint_inbox.h"
#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/estimator/loop/loop_closure.h"

namespace swlio::ipc {
class Subscriber;
}

namespace swlio::daemon {

struct LoopClosureQueues {
  SpscQueue<KeyframePtr>* keyframes_in = nullptr;       ///< optimizer → loop_closure
  SpscQueue<MapCorrection>* corrections_out = nullptr;  ///< loop_closure → publisher
  SpscQueue<GnssFix>* gnss_in = nullptr;                ///< propagator → loop_closure (optional)
};

struct LoopClosureCounters {
  bool enabled = false;
  uint64_t keyframes = 0;  ///< taken from the optimizer
  uint64_t nodes = 0;
  uint64_t attempts = 0;
  uint64_t accepted = 0;
  uint64_t rejected = 0;
  uint64_t loops_switched_off = 0;  ///< by the pose graph's consistency check
  double last_attempt_ms = 0.0;     ///< wall time of the last verification (+ graph solve)
  double max_attempt_ms = 0.0;
  /// The current correction's size (|translation| and rotation angle of T_map_odom).
  double correction_m = 0.0;
  double correction_rad = 0.0;
  bool gnss = false;               ///< GNSS factors configured
  uint64_t gnss_fixes = 0;         ///< taken from the propagator
  uint64_t gnss_edges = 0;         ///< in the graph
  uint64_t gnss_switched_off = 0;  ///< outliers (multipath) switched off
  uint64_t gnss_rejected = 0;      ///< fix type, accuracy, rate, no odometry around it, innovation
  bool gnss_aligned = false;       ///< the map-to-ENU alignment is estimated
  double enu_yaw_rad = 0.0;        ///< of the map frame in ENU
  uint64_t hints = 0;              ///< operators' pose hints taken (re-anchoring)
  uint64_t hints_refused = 0;
  std::string last_hint;  ///< the last hint's outcome; empty: none yet
};

class LoopClosureThread {
 public:
  LoopClosureThread(const estimator::LoopClosureConfig& config, const LoopClosureQueues& queues);
  /// Publish the map cloud through `map` (not owned; null: no map cloud). Call before Run.
  void PublishMapTo(MapPublisher* map) { map_ = map; }
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  /// Relaxed copies (any thread).
  LoopClosureCounters counters() const;
  /// The graph as a saved map at `path`, its merged cloud at `pcd_path` (saved_map.h,
  /// map_pcd.h), beating `beat` between the stages; call on this thread (RequestSave) or after
  /// Run returned. Returns the node count; *error set on failure.
  size_t SaveMap(const std::string& path,
                 const std::string& pcd_path,
                 std::string* error,
                 const Watchdog::Handle& beat = {}) const;
  /// An operator's save-map (swlioctl save-map PATH; control thread only): saved on this thread,
  /// which owns the graph, at its next loop (≤ 100 ms), to PATH and PATH.pcd. False when
  /// requests are already queued.
  bool RequestSave(std::shared_ptr<PendingCommand> command);
  /// Pose hints: from /initialpose through `reader` (not owned; call before Run), and from
  /// swlioctl (control thread; false when requests are queued). T_base_imu: see SetBaseFrame.
  void ReadHintsFrom(ipc::Subscriber* reader, const std::string& map_frame) {
    hints_.ReadFrom(reader, map_frame);
  }
  bool RequestHint(PoseHint hint) { return hints_.Request(std::move(hint)); }
  void SetBaseFrame(const Eigen::Isometry3d& T_base_imu) { T_base_imu_ = T_base_imu; }

 private:
  void Handle(const estimator::KeyframeCloud& keyframe);
  /// The fixes queued by the propagator into the graph.
  void DrainGnss();
  /// A solved graph's new correction to the publisher (and the map cloud).
  void ApplyCorrection(const estimator::LoopClosureUpdate& u, int64_t t_ns);
  void PublishGnssCounters();
  /// Publishes the corrected map when a correction is pending and the period is over.
  void PublishMapIfDue(const Watchdog::Handle& beat);
  /// Executes the queued save-map requests.
  void ServeSaves(const Watchdog::Handle& beat);
  /// Re-anchors the map frame at a pose hint (or refuses it), answers and logs it.
  void ApplyHint(const PoseHint& hint);

  estimator::LoopClosure closure_;
  HintInbox hints_{"loop_closure"};
  Eigen::Isometry3d T_base_imu_ = Eigen::Isometry3d::Identity();
  KeyframePtr newest_;             ///< the keyframe a hint re-anchors at
  mutable std::mutex hint_mutex_;  ///< guards the hint fields of hint_
  LoopClosureCounters hint_;       ///< only the hint fields are used
  /// control → loop_closure: save-map requests (a few; one more is refused as busy).
  SpscQueue<std::shared_ptr<PendingCommand>> saves_{"save_requests", "control", "loop_closure", 4};
  LoopClosureQueues q_;
  MapPublisher* map_ = nullptr;
  std::atomic<uint64_t> keyframes_{0}, nodes_{0}, attempts_{0}, accepted_{0}, rejected_{0},
      switched_off_{0};
  std::atomic<double> last_ms_{0.0}, max_ms_{0.0}, correction_m_{0.0}, correction_rad_{0.0};
  std::atomic<uint64_t> gnss_fixes_{0}, gnss_edges_{0}, gnss_switched_off_{0}, gnss_rejected_{0};
  std::atomic<bool> gnss_aligned_{false};
  std::atomic<double> enu_yaw_rad_{0.0};
  const bool gnss_;
};

}  // namespace swlio::daemon

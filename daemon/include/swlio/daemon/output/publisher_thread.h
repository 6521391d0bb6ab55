#pragma once
/// @file
/// The publisher thread: writes the IMU-rate pose as soon as the propagator hands it over,
/// the odometry of every sweep, the keyframe path (latched; on change, at most 1 Hz) and the
/// health at 1 Hz. The only thread that calls into DDS.
///
/// With loop closure, every pose and odometry is published in the map frame: the estimator's
/// (odometry-frame) pose times the map correction, which follows the loop-closure thread's
/// corrections at a bounded rate (CorrectionSlew), so the planner never sees a jump larger
/// than the configured rates allow (the covariance is left in the odometry frame's axes: the
/// correction's rotation is a fraction of a degree). Keyframes join the path as published;
/// after each loop the path is replaced by the pose graph's nodes (one per metre) at their
/// corrected poses, so the planner sees the whole corrected trajectory.
///
/// Stamps: each message's stamp is converted once, when it is written, from the daemon's time
/// by the StampClock (stamp_clock.h; CLOCK_REALTIME by default), whose offset this thread
/// samples at every wake; a wall-clock step is logged once with its size. A keyframe keeps in
/// the path the stamp its odometry was published with. Without a StampClock the stamps are the
/// host's CLOCK_MONOTONIC.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "swlio/daemon/output/message_conversion.h"
#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/runtime/latency_histogram.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/estimator/loop/correction_slew.h"
#include "swlio/ipc/publisher.h"

namespace swlio::daemon {

struct PublisherQueues {
  SpscQueue<ImuRatePose>* poses_in = nullptr;          ///< propagator → publisher
  SpscQueue<SweepEstimate>* odometry_in = nullptr;     ///< optimizer → publisher
  Doorbell* wake = nullptr;                            ///< rung by poses_in and odometry_in
  SpscQueue<MapCorrection>* corrections_in = nullptr;  ///< loop_closure → publisher (optional)
};

struct PublisherCounters {
  uint64_t poses = 0;
  uint64_t odometry = 0;
  uint64_t health = 0;
  uint64_t paths = 0;
  uint64_t failures = 0;  ///< writes DDS refused
  /// Poses and odometry not published because a position or orientation was not finite
  /// (never sent to the planner; a non-zero count is a bug to report).
  uint64_t non_finite = 0;
  /// Poses and odometry not published because the pose was not yet localized in the saved map
  /// (HoldUntilLocalized): the planner gets map-frame poses only.
  uint64_t held = 0;
  /// From the read(2) that returned an IMU sample to its pose's DDS write (host clock).
  LatencyHistogram::Counts pose_latency{};
};

class PublisherThread {
 public:
  /// Builds the health message (called from this thread, once a second).
  using HealthFn = std::function<ipc::DiagnosticArray(int64_t now_ns)>;
  /// `publisher` may be null (no DDS: a test, or --no-dds): then nothing is written but the
  /// queues are still drained and counted.
  PublisherThread(ipc::Publisher* publisher,
                  FrameIds frames,
                  const PublisherQueues& queues,
                  const TimeScale& time,
                  HealthFn health,
                  int64_t health_period_ns = 1'000'000'000,
                  size_t path_max_poses = 5000,
                  const estimator::CorrectionSlewConfig& slew = {});
  /// Localization in a saved map: publish no pose or odometry until the first correction that
  /// jumps (the relocalization) has arrived. Call before Run.
  void HoldUntilLocalized() { holding_ = true; }
  /// Stamps through `stamps` (not owned; outlives Run), sampled by this thread. Call before Run.
  void StampWith(StampClock* stamps) { stamps_ = stamps; }
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  PublisherCounters counters() const;
  /// The keyframes the path holds (the newest path_max_poses); read after Run returned.
  const std::deque<ipc::PoseStamped>& keyframes() const { return keyframes_; }

 private:
  void TakeCorrections();
  /// Samples the stamp clock's offset; logs a wall-clock step.
  void UpdateStampClock();
  /// A daemon time (time-scaled) as the message stamp.
  int64_t Stamp(int64_t t_daemon_ns) const;
  /// The keyframe path becomes the graph's nodes at their corrected poses (newest
  /// path_max_poses); later keyframes are appended as published.
  void ReplacePath(const std::vector<estimator::MapNode>& nodes);
  /// `s` moved into the map frame by the current correction (stepped to `s.t_ns`).
  State Corrected(State s);
  void WritePose(const ImuRatePose& pose);
  void WriteOdometry(const SweepEstimate& e);
  void Periodic(int64_t now_ns);
  void Count(bool ok, std::atomic<uint64_t>* counter);

  ipc::Publisher* publisher_;
  FrameIds frames_;
  PublisherQueues q_;
  TimeScale time_;
  HealthFn health_;
  int64_t health_period_ns_;
  int64_t next_health_ns_ = 0;
  size_t path_max_poses_;
  estimator::CorrectionSlew slew_;
  std::deque<ipc::PoseStamped> keyframes_;
  ipc::Path path_;  ///< the message, filled from keyframes_ when published
  bool path_changed_ = false;
  bool holding_ = false;
  StampClock* stamps_ = nullptr;
  Eigen::Vector3d last_gyro_imu_radps_ = Eigen::Vector3d::Zero();
  LatencyHistogram pose_latency_;
  std::atomic<uint64_t> poses_{0}, odometry_{0}, health_count_{0}, paths_{0}, failures_{0},
      non_finite_{0}, held_{0};
};

}  // namespace swlio::daemon

#pragma once
/// @file
/// The publisher thread: writes the IMU-rate pose as soon as the propagator hands it over,
/// the odometry of every sweep, the keyframe path (latched; on change, at most 1 Hz), the
/// health at 1 Hz, and the transforms of REP 105. The only thread that calls into DDS.
///
/// Poses, odometry and the path are the robot base's (base_link; message_conversion.h). The
/// pose, the odometry and the path are in the map frame: the estimator's (odom-frame) pose
/// times the map correction C, which follows the loop-closure thread's corrections at a bounded
/// rate (CorrectionSlew), so the planner never sees a jump larger than the configured rates
/// allow (the covariance is left in the odom frame's axes: the correction's rotation is a
/// fraction of a degree). Keyframes join the path as published; after each loop the path is
/// replaced by the pose graph's nodes (one per metre) at their corrected poses, so the planner
/// sees the whole corrected trajectory.
///
/// REP 105: odom is the estimator's own frame, continuous (no loop correction ever reaches
/// it). /tf gets odom → base_link with every pose (IMU rate) and map → odom = C, stamped like
/// the pose it was applied to, with the first pose whose C differs from the one sent last and
/// otherwise at least every SetMapOdomPeriod (pose time); so map → odom (the latest at or
/// before a pose's stamp) ∘ odom → base_link is the published map-frame pose. Map → odom goes
/// out with poses only: a sweep's odometry may step C but takes the C then current. /tf_static gets
/// base_link → imu and base_link → lidar once at start. The odom-frame odometry (nav_msgs/Odometry,
/// frame odom) goes out beside the map-frame one. Before the first localization in a saved map
/// (HoldUntilLocalized) only the odom-frame outputs are published.
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

#include "swlio/daemon/output/correction_cell.h"
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
  uint64_t odom_odometry = 0;   ///< odom-frame odometry
  uint64_t transforms = 0;      ///< /tf and /tf_static samples
  uint64_t static_resends = 0;  ///< /tf_static sent again: the extrinsic was refined online
  uint64_t failures = 0;        ///< writes DDS refused
  /// Poses and odometry not published because a position or orientation was not finite
  /// (never sent to the planner; a non-zero count is a bug to report).
  uint64_t non_finite = 0;
  /// Poses and odometry not published because the pose was not yet localized in the saved map
  /// (HoldUntilLocalized): the planner gets map-frame poses only (odom-frame outputs go on).
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
                  OutputFrames frames,
                  const PublisherQueues& queues,
                  const TimeScale& time,
                  HealthFn health,
                  int64_t health_period_ns = 1'000'000'000,
                  size_t path_max_poses = 5000,
                  const estimator::CorrectionSlewConfig& slew = {});
  /// Localization in a saved map: publish no pose or odometry until the first correction that
  /// jumps (the relocalization) has arrived. Call before Run.
  void HoldUntilLocalized() { holding_ = true; }
  /// The correction this thread applies now (any thread may read it).
  const CorrectionCell& correction() const { return correction_cell_; }
  /// Stamps through `stamps` (not owned; outlives Run), sampled by this thread. Call before Run.
  void StampWith(StampClock* stamps) { stamps_ = stamps; }
  /// map → odom goes out at least this often (daemon time) while poses flow, besides every
  /// change (0: with every pose). Call before Run.
  void SetMapOdomPeriod(int64_t period_ns) { map_odom_period_ns_ = period_ns; }
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
  /// Steps the map correction C to `t_ns` (for the IMU pose `T_odom_imu`) and returns it. With
  /// `send` (an IMU-rate pose), adds map → odom to tf_ when C is not the one sent last or the
  /// period passed since.
  const Eigen::Isometry3d& StepCorrection(int64_t t_ns,
                                          const Eigen::Isometry3d& T_odom_imu,
                                          bool send);
  void WritePose(const ImuRatePose& pose);
  void WriteOdometry(const SweepEstimate& e);
  /// Re-sends /tf_static when the estimator's extrinsic moved (online refinement).
  void FollowExtrinsic(const SweepEstimate& e);
  void WriteTf();
  void WriteStaticTf();
  void Periodic(int64_t now_ns);
  void Count(bool ok, std::atomic<uint64_t>* counter);

  ipc::Publisher* publisher_;
  OutputFrames frames_;
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
  bool stored_correction_ = false;  ///< correction_cell_ holds stored_T_map_odom_
  StampClock* stamps_ = nullptr;
  ipc::TFMessage tf_;  ///< the /tf sample being built
  int64_t map_odom_period_ns_ = 100'000'000;
  Eigen::Isometry3d stored_T_map_odom_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d sent_T_map_odom_ = Eigen::Isometry3d::Identity();
  int64_t sent_map_odom_t_ns_ = 0;  ///< daemon time of the newest map → odom sent
  bool sent_map_odom_ = false;
  Eigen::Vector3d last_gyro_imu_radps_ = Eigen::Vector3d::Zero();
  LatencyHistogram pose_latency_;
  std::atomic<uint64_t> poses_{0}, odometry_{0}, health_count_{0}, paths_{0}, failures_{0},
      non_finite_{0}, held_{0}, odom_odometry_{0}, transforms_{0}, static_resends_{0};
  CorrectionCell correction_cell_;
};

}  // namespace swlio::daemon

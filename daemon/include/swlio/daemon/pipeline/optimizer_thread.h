#pragma once
/// @file
/// The optimizer thread: decodes and assembles the LiDAR datagrams into sweeps on the host
/// clock (LidarStage), feeds them and the propagator's IMU samples to the estimator
/// (EstimatorRunner: de-skew, features, matching, window optimization, marginalization), and
/// sends each sweep's result to the propagator (new state) and the publisher (odometry).
///
/// Tracking state per sweep: initializing until the estimator has a state; tracking when the
/// sweep registered with no degenerate direction; degraded when it did not register (the IMU
/// prediction was kept) or some direction was left to the IMU; lost after `kLostAfterSweeps`
/// consecutive sweeps without registration.

#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <utility>

#include "swlio/daemon/control/pending_command.h"
#include "swlio/daemon/output/sweep_publisher.h"
#include "swlio/daemon/pipeline/estimator_runner.h"
#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/pipeline/sweep_shedding.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/daemon/sensors/lidar_stage.h"

namespace swlio::daemon {

struct OptimizerQueues {
  SpscQueue<LidarPacket>* lidar_in = nullptr;        ///< lidar_rx → optimizer
  SpscQueue<ImuSample>* imu_in = nullptr;            ///< propagator → optimizer
  SpscQueue<SweepEstimate>* states_out = nullptr;    ///< optimizer → propagator
  SpscQueue<SweepEstimate>* odometry_out = nullptr;  ///< optimizer → publisher
  Doorbell* wake = nullptr;                          ///< rung by lidar_in and imu_in
  SpscQueue<KeyframePtr>* keyframes_out = nullptr;   ///< optimizer → loop_closure (optional)
  SpscQueue<WheelOdometry>* wheel_in = nullptr;      ///< can_rx → optimizer (optional)
};

struct OptimizerCounters {
  LidarStageCounters lidar;
  drivers::ClockModelStats lidar_clock;
  uint64_t processed = 0;  ///< sweeps the estimator took
  uint64_t dropped_waiting = 0;
  uint64_t map_points = 0;      ///< points in the estimator's local maps (bounded: radius, voxels)
  uint64_t skipped_behind = 0;  ///< sweeps skipped while the estimator ran behind (SweepShedding)
  TrackingState tracking = TrackingState::kInitializing;
  int degenerate_directions = 0;
  double last_update_ms = 0.0;
  double max_update_ms = 0.0;      ///< since start
  uint64_t wheel_factors = 0;      ///< window frames with a wheel velocity factor
  uint64_t wheel_rejected = 0;     ///< wheel measurements the slip gate refused
  bool standing_still = false;     ///< the newest sweep's frame was taken for rest
  uint64_t standstill_sweeps = 0;  ///< frames with a zero-velocity factor so far
  /// The estimator restarted: it found its state diverged, or an operator reset it.
  uint64_t reinitializations = 0;
  uint64_t operator_resets = 0;  ///< of those, resets asked for (swlioctl reset)
  /// The LiDAR–IMU time offset applied to the IMU samples, its estimate and how many sweeps
  /// updated it (estimator/window/time_offset_estimator.h).
  estimator::TimeOffsetStatus time_offset;
  /// Local-map points later sweeps saw through (moving objects) and removed, so far.
  uint64_t dynamic_removed = 0;
  bool recovering = false;  ///< re-initializing after the last one
  /// How long the IMU alone has carried the state (IMU samples newer than the last processed
  /// sweep by more than kImuOnlyDegradedNs: the LiDAR is out); the state then reads degraded.
  double imu_only_s = 0.0;
  /// Host time (CLOCK_MONOTONIC) of the end of the last processed sweep (0: none yet): the
  /// health's sweep age, and which sweeps a snapshot's state describes when the estimator runs
  /// behind its input.
  int64_t last_sweep_end_host_ns = 0;
  /// Why the last one happened (estimator::ToString(DivergenceReason); "none" before any).
  const char* last_divergence = "none";
};

class OptimizerThread {
 public:
  static constexpr int kLostAfterSweeps = 10;
  static constexpr int64_t kImuOnlyDegradedNs = 300'000'000;  ///< three sweeps at 10 Hz

  /// `max_sweep_lag_ns` (daemon time): SweepShedding's limit; 0 never skips a sweep.
  OptimizerThread(const drivers::LidarConfig& lidar,
                  const EstimatorSetup& setup,
                  const OptimizerQueues& queues,
                  const TimeScale& time = {},
                  int64_t max_sweep_lag_ns = 0);
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  OptimizerCounters counters() const;
  /// An operator's reset (swlioctl reset; control thread only): the estimator re-initializes
  /// at its next loop (≤ 20 ms), as after a divergence (EstimatorRunner::Reset), and the
  /// propagator drops its state. False when requests are already queued.
  bool RequestReset(std::shared_ptr<PendingCommand> command);
  /// Publish each tracked sweep through `sweeps` (not owned; null: none). Call before Run.
  void PublishSweepsTo(SweepPublisher* sweeps) { sweeps_ = sweeps; }
  /// Also pushes every tracked sweep's state, stamped on the host clock as swlio-replay writes
  /// it, to `record` (the recorder's odometry.tum). Call before Run.
  void RecordOdometryTo(SpscQueue<State>* record) { record_ = record; }

 private:
  void OnResult(const Scan& scan, const estimator::WindowResult& result);
  TrackingState Classify(const estimator::OdometryResult& r);
  void DrainImu();
  void DrainWheel();
  void DrainLidar();
  int64_t LastRxOf(int64_t t_end_ns) const;
  void Publish();
  /// Executes the queued reset requests.
  void ServeResets();

  // In the order clang-tidy's padding check finds tightest (the queue is cache-line aligned).
  /// control → optimizer: reset requests (a few; one more is refused as busy).
  SpscQueue<std::shared_ptr<PendingCommand>> resets_{"reset_requests", "control", "optimizer", 4};
  SweepPublisher* sweeps_ = nullptr;
  SpscQueue<State>* record_ = nullptr;
  uint64_t processed_ = 0;
  uint64_t reinitializations_ = 0;
  uint64_t operator_resets_ = 0;
  uint64_t wheel_factors_ = 0, wheel_rejected_ = 0;
  uint64_t standstill_sweeps_ = 0;
  estimator::TimeOffsetStatus time_offset_;
  uint64_t dynamic_removed_ = 0;
  int64_t newest_imu_t_ns_ = 0;  ///< daemon time
  int64_t last_sweep_t_ns_ = 0;  ///< end of the last processed sweep, daemon time
  double last_ms_ = 0.0;
  double max_ms_ = 0.0;
  TimeScale time_;
  SweepShedding shedding_;
  // The copy health reads (not an rx thread: a short lock per sweep is fine here).
  mutable std::mutex snapshot_mutex_;
  OptimizerQueues q_;
  HostSweep sweep_;
  /// (sweep end, host receive time of its last packet) of the sweeps the runner holds.
  std::deque<std::pair<int64_t, int64_t>> rx_by_end_;
  EstimatorRunner runner_;
  OptimizerCounters snapshot_;
  LidarStage lidar_;
  int failed_in_a_row_ = 0;
  estimator::DivergenceReason last_divergence_ = estimator::DivergenceReason::kNone;
  int degenerate_ = 0;
  TrackingState tracking_ = TrackingState::kInitializing;
  bool recovering_ = false;  ///< re-initializing after a divergence: lost until tracked again
  bool standing_still_ = false;
};

}  // namespace swlio::daemon

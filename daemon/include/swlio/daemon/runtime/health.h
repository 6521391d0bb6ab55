#pragma once
/// @file
/// The daemon's health: every thread's counters in one snapshot, turned into the published
/// diagnostic_msgs/DiagnosticArray (one status per sensor, the estimator, the queues) and the
/// log's status line. Rates and gaps are computed between consecutive reports.

#include <cstdint>
#include <string>
#include <vector>

#include "swlio/daemon/output/map_publisher.h"
#include "swlio/daemon/output/publisher_thread.h"
#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/daemon/output/sweep_publisher.h"
#include "swlio/daemon/pipeline/localization_thread.h"
#include "swlio/daemon/pipeline/loop_closure_thread.h"
#include "swlio/daemon/pipeline/optimizer_thread.h"
#include "swlio/daemon/pipeline/propagator_thread.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/recording/recorder.h"
#include "swlio/daemon/sensors/can_rx.h"
#include "swlio/daemon/sensors/imu_rx.h"
#include "swlio/daemon/sensors/lidar_rx.h"
#include "swlio/ipc/messages.h"

namespace swlio::daemon {

struct HealthSnapshot {
  int64_t t_ns = 0;  ///< host time of the snapshot
  LidarRxCounters lidar_rx;
  ImuRxCounters imu_rx;
  bool can_enabled = false;
  CanRxCounters can_rx;
  PropagatorCounters propagator;
  OptimizerCounters optimizer;
  PublisherCounters publisher;
  LoopClosureCounters loop_closure;   ///< `enabled` false when loop closure is off
  LocalizationCounters localization;  ///< `enabled` false unless localizing in a saved map
  MapPublishCounters map;             ///< `enabled` false unless the map cloud is published
  SweepPublishCounters sweeps;        ///< `enabled` false unless ipc.sweep_topic is published
  StampClockCounters stamp_clock;     ///< the published stamps' clock and its offset
  bool recording = false;             ///< --record or the black box (record.ring)
  RecorderCounters recorder;
  std::vector<QueueCounters> queues;
};

/// Rates over the last interval (per second), from two snapshots.
struct HealthRates {
  double lidar_packets_hz = 0.0;
  double sweeps_hz = 0.0;
  double imu_hz = 0.0;
  double poses_hz = 0.0;
  double can_frames_hz = 0.0;
  /// Sensor clock jumps (ClockModel restarts) since the previous report; on the first report,
  /// since the start.
  uint64_t lidar_clock_jumps = 0;
  uint64_t imu_clock_jumps = 0;
  /// Steps of the host's wall clock (StampClock) since the previous report.
  uint64_t wall_clock_steps = 0;
  /// Sweeps skipped because the estimator fell behind (SweepShedding), since the previous
  /// report: the CPU does not suffice.
  uint64_t sweeps_skipped_behind = 0;
  /// Latencies over the last interval (on the first report, since the start).
  LatencySummary imu_read_lag;    ///< sample taken → read(2) (PropagatorCounters::read_lag)
  LatencySummary lidar_read_lag;  ///< kernel receive stamp → recvmmsg(2)
  LatencySummary pose_latency;    ///< IMU read → pose written to DDS
};

class HealthReporter {
 public:
  /// Rates against the previous call's snapshot (zeros on the first call).
  HealthRates Rates(const HealthSnapshot& now);
  /// The DiagnosticArray for `now` (calls Rates).
  ipc::DiagnosticArray Diagnostics(const HealthSnapshot& now);
  /// One log line (calls Rates).
  std::string StatusLine(const HealthSnapshot& now);

 private:
  HealthSnapshot previous_;
  bool have_previous_ = false;
};

/// The recording's status (the black box's, or --record's): ring bounds, incidents, and a
/// stop (a full disk) as an error.
ipc::DiagnosticStatus RecorderStatus(const HealthSnapshot& s);

/// The IMU's Xbus framing counters as health reports them: the configuration handshakes'
/// (framed on imu_rx) plus the stream's (decoded on the propagator).
uint64_t ImuChecksumErrors(const HealthSnapshot& s);
uint64_t ImuSkippedBytes(const HealthSnapshot& s);

/// Total drops over every queue and receiver: what "lossless" is checked against.
uint64_t TotalDrops(const HealthSnapshot& s);

/// One log line for `now` with the given rates (HealthReporter::StatusLine without the rates).
std::string StatusLine(const HealthSnapshot& now, const HealthRates& rates);

/// A warning per sensor whose clock jumped since the previous report (rates from the same
/// HealthReporter::Rates call): with the new offset and drift, and what it means. Without it a
/// field engineer saw only the estimator's divergence that mis-timed sweeps caused.
std::vector<std::string> ClockJumpWarnings(const HealthSnapshot& now, const HealthRates& rates);

}  // namespace swlio::daemon

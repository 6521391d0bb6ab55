#pragma once
/// @file
/// The propagator thread: takes the imu_rx thread's samples, maps them to host time
/// (ImuStage), hands each to the optimizer, and integrates it at once from the latest
/// optimized state (ImuRatePropagator) into an IMU-rate pose for the publisher. A new
/// optimized state is applied before the next sample. The optimizer never blocks it: they
/// share only queues.
///
/// The IMU-rate pose carries the last optimized pose covariance with the position part grown
/// by the velocity's: P_pp + P_vv·Δt² + P_pv·Δt + P_vp·Δt, Δt the time since that state (the
/// IMU-only stretch; grows while the LiDAR is out).

#include <atomic>
#include <cstdint>

#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/runtime/latency_histogram.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/daemon/sensors/imu_stage.h"
#include "swlio/estimator/imu/imu_rate_propagator.h"

namespace swlio::daemon {

struct PropagatorQueues {
  SpscQueue<ImuRaw>* imu_in = nullptr;            ///< imu_rx → propagator
  SpscQueue<SweepEstimate>* states_in = nullptr;  ///< optimizer → propagator
  SpscQueue<ImuSample>* imu_out = nullptr;        ///< propagator → optimizer
  SpscQueue<ImuRatePose>* poses_out = nullptr;    ///< propagator → publisher
  /// propagator → loop_closure: usable GNSS fixes at their IMU sample's host time (optional).
  SpscQueue<GnssFix>* gnss_out = nullptr;
};

struct PropagatorCounters {
  uint64_t samples = 0;  ///< mapped to host time
  uint64_t dropped = 0;  ///< no SampleTimeFine, incomplete or non-finite, out of order
  uint64_t invalid = 0;  ///< of those: incomplete or non-finite values
  uint64_t poses = 0;    ///< IMU-rate poses sent to the publisher
  uint64_t states = 0;   ///< optimized states applied
  uint64_t clock_jumps = 0;
  double clock_offset_ns = 0.0;  ///< host − sensor (SampleTimeFine)
  double clock_drift_ppm = 0.0;
  int64_t last_sample_t_ns = 0;  ///< host time of the newest sample
  uint64_t gnss_fixes = 0;       ///< usable GnssPvtData items passed on
  uint64_t gnss_unusable = 0;    ///< items without a fix (or with impossible values)
  /// How late each sample was read: the read(2) that returned its frame, after the time it was
  /// taken (host clock). Serial delivery (the adapter's bursts), the kernel's tty worker and
  /// the imu_rx thread's own scheduling all add to it.
  LatencyHistogram::Counts read_lag{};
};

class PropagatorThread {
 public:
  PropagatorThread(int64_t imu_baud,
                   const estimator::ImuRatePropagatorConfig& config,
                   const PropagatorQueues& queues,
                   const TimeScale& time = {});
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  /// A copy taken under no lock: written by Run every 100 samples and on idle wake-ups.
  PropagatorCounters counters() const;

 private:
  void ApplyStates();
  void Handle(const ImuRaw& raw);
  void Publish();

  PropagatorQueues q_;
  TimeScale time_;
  ImuStage stage_;
  estimator::ImuRatePropagator propagator_;
  estimator::StateCovariance covariance_;
  uint64_t poses_ = 0;
  uint64_t states_ = 0;
  uint64_t gnss_fixes_ = 0, gnss_unusable_ = 0;
  int64_t last_sample_t_ns_ = 0;
  // The snapshot health reads (relaxed atomics; fields may be from adjacent updates).
  std::atomic<uint64_t> a_samples_{0}, a_dropped_{0}, a_invalid_{0}, a_poses_{0}, a_states_{0},
      a_jumps_{0}, a_gnss_fixes_{0}, a_gnss_unusable_{0};
  std::atomic<int64_t> a_last_sample_t_ns_{0};
  LatencyHistogram read_lag_;
  std::atomic<double> a_offset_ns_{0.0}, a_drift_ppm_{0.0};
};

/// The grown pose covariance described in the file comment.
ipc::Covariance6 GrownPoseCovariance(const estimator::StateCovariance& covariance, double dt_s);

}  // namespace swlio::daemon

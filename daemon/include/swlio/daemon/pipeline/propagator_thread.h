#pragma once
/// @file
/// The propagator thread: takes the serial bytes the imu_rx thread read, decodes them
/// (XsensStreamDecoder: Xbus framing, MTData2, PacketCounter gaps; restarted where the chunks'
/// open epoch changes), maps each sample to host time (ImuStage), hands it to the optimizer,
/// and integrates it at once from the latest optimized state (ImuRatePropagator) into an
/// IMU-rate pose for the publisher. A new optimized state is applied before the next sample.
/// The optimizer never blocks it: they share only queues.
///
/// The IMU-rate pose carries the last optimized pose covariance with the position part grown
/// by the velocity's: P_pp + P_vv·Δt² + P_pv·Δt + P_vp·Δt, Δt the time since that state (the
/// IMU-only stretch; grows while the LiDAR is out).
///
/// A backlog (serial bytes that reach `read` late, e.g. from a kernel tty worker starved for
/// seconds) arrives as a few reads holding thousands of samples. Every sample still goes to the
/// optimizer, and every one is propagated, but a pose read more than `kStalePoseNs` after its
/// sample was taken is published only if it is the newest of its read: one pose per read
/// while the backlog drains, instead of thousands of outdated ones flooding the publisher and
/// DDS when the CPU is scarcest (counted as `poses_coalesced`).

#include <atomic>
#include <cstdint>
#include <optional>

#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/runtime/latency_histogram.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/daemon/sensors/imu_stage.h"
#include "swlio/drivers/xsens/xsens_stream_decoder.h"
#include "swlio/estimator/imu/imu_rate_propagator.h"

namespace swlio::daemon {

struct PropagatorQueues {
  SpscQueue<SerialChunk>* serial_in = nullptr;    ///< imu_rx → propagator: the stream's bytes
  SpscQueue<SweepEstimate>* states_in = nullptr;  ///< optimizer → propagator
  SpscQueue<ImuSample>* imu_out = nullptr;        ///< propagator → optimizer
  SpscQueue<ImuRatePose>* poses_out = nullptr;    ///< propagator → publisher
  /// propagator → loop_closure: usable GNSS fixes at their IMU sample's host time (optional).
  SpscQueue<GnssFix>* gnss_out = nullptr;
};

/// The serial stream's decoding, on the propagator thread (XsensStreamStats).
struct ImuDecodeCounters {
  uint64_t samples = 0;          ///< MTData2 messages decoded
  uint64_t checksum_errors = 0;  ///< Xbus frames whose checksum failed
  uint64_t skipped_bytes = 0;    ///< bytes skipped resynchronizing (garbage, cut frames)
  uint64_t missing_packets = 0;  ///< lost according to the PacketCounter
  uint64_t counter_gaps = 0;     ///< PacketCounter discontinuities
  uint64_t restarts = 0;         ///< streams begun again after a re-open of the device
};

struct PropagatorCounters {
  ImuDecodeCounters decode;
  uint64_t samples = 0;          ///< mapped to host time
  uint64_t dropped = 0;          ///< no SampleTimeFine, incomplete or non-finite, out of order
  uint64_t invalid = 0;          ///< of those: incomplete or non-finite values
  uint64_t poses = 0;            ///< IMU-rate poses sent to the publisher
  uint64_t poses_coalesced = 0;  ///< stale poses not sent: a newer one of the same read was
  uint64_t states = 0;           ///< optimized states applied
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
  /// A pose read this long after its sample was taken is stale (host clock): 25 cm at 1 m/s,
  /// of no use to a controller except as the newest one there is.
  static constexpr int64_t kStalePoseNs = 250'000'000;

  PropagatorThread(int64_t imu_baud,
                   const estimator::ImuRatePropagatorConfig& config,
                   const PropagatorQueues& queues,
                   const TimeScale& time = {});
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  /// A copy taken under no lock: written by Run every 100 decoded samples and on idle
  /// wake-ups.
  PropagatorCounters counters() const;

 private:
  void ApplyStates();
  /// The decoder's sink: one decoded sample.
  void OnSample(const drivers::xsens::MtData2Sample& sample, int64_t t_rx_ns);
  void Handle(const ImuRaw& raw);
  /// Sends `pose`, or holds it while it is stale (the newest held one goes at the read's end).
  void Offer(const ImuRatePose& pose, bool stale);
  void SendHeldPose();
  void Publish();

  PropagatorQueues q_;
  TimeScale time_;
  drivers::xsens::XsensStreamDecoder decoder_;
  uint64_t since_publish_ = 0;  ///< samples decoded since the last Publish
  ImuStage stage_;
  estimator::ImuRatePropagator propagator_;
  estimator::StateCovariance covariance_;
  uint64_t poses_ = 0;
  uint64_t poses_coalesced_ = 0;
  std::optional<ImuRatePose> held_pose_;  ///< the newest stale pose of the current read
  uint64_t states_ = 0;
  uint64_t gnss_fixes_ = 0, gnss_unusable_ = 0;
  int64_t last_sample_t_ns_ = 0;
  int64_t imu_time_offset_ns_ = 0;  ///< the estimator's, from its last SweepEstimate
  // The snapshot health reads (relaxed atomics; fields may be from adjacent updates).
  std::atomic<uint64_t> a_samples_{0}, a_dropped_{0}, a_invalid_{0}, a_poses_{0},
      a_poses_coalesced_{0}, a_states_{0}, a_jumps_{0}, a_gnss_fixes_{0}, a_gnss_unusable_{0};
  std::atomic<uint64_t> a_decoded_{0}, a_checksum_errors_{0}, a_skipped_bytes_{0},
      a_missing_packets_{0}, a_counter_gaps_{0}, a_restarts_{0};
  std::atomic<int64_t> a_last_sample_t_ns_{0};
  LatencyHistogram read_lag_;
  std::atomic<double> a_offset_ns_{0.0}, a_drift_ppm_{0.0};
};

/// The grown pose covariance described in the file comment.
ipc::Covariance6 GrownPoseCovariance(const estimator::StateCovariance& covariance, double dt_s);

}  // namespace swlio::daemon

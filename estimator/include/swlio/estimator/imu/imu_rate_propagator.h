#pragma once
/// @file
/// The IMU-rate output: every IMU sample is integrated at once from the latest optimized state,
/// so a pose is available per sample whatever the optimizer is doing (LIO-SAM's
/// imuPreintegration thread is the pattern; design.md "propagator thread").
///
/// The samples are kept in a fixed ring buffer. When the optimizer delivers a new state at t_k
/// (pose, velocity, biases), the samples up to t_k are dropped except the last one, and the
/// samples after t_k (the first of them holds the interval that straddles t_k) are
/// integrated again from the new state: the output then equals integrating from that state
/// through the same samples (`ImuPropagator`, whose step function `StrapdownStep` is shared).
///
/// Continuity (REP 105's odom): a new state moves the propagated pose by the correction the
/// optimizer made (millimetres). With `rebase_rate_mps` > 0 the output does not jump: it keeps
/// the pose it had and takes the correction in at that rate (and `rebase_rate_radps`), so each
/// step is the motion plus at most rate × period. A correction beyond `rebase_max_m` /
/// `rebase_max_rad` (a re-initialization, a registration that moved far) is taken at once: an
/// output that lags the estimate by decimetres for seconds is worse than one jump.
///
/// Pure and single-threaded: no threads, clocks or locks; allocates only in the constructor.
/// The caller (the daemon's propagator thread) feeds samples and states in time order and
/// publishes the outputs.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"

namespace swlio::estimator {

struct ImuRatePropagatorConfig {
  double gravity_mps2 = 9.80665;  ///< local gravity, m/s²
  /// Samples held for re-propagation: 2 s at 400 Hz, far longer than an optimizer round. When
  /// full the oldest is dropped (counted); a state older than the buffer is then integrated
  /// without the dropped samples.
  size_t buffer_samples = 800;
  /// Re-basing: 0 takes each correction at once (the output equals integrating from the state).
  double rebase_rate_mps = 0.0;
  double rebase_rate_radps = 0.0;
  double rebase_max_m = 0.1;
  double rebase_max_rad = 0.05;

  ConfigIssues Validate() const;
};

/// One output: the state propagated to a sample's time.
struct ImuRateOutput {
  State state;  ///< at the sample's time, with the biases of the last optimized state
  Eigen::Vector3d gyro_imu_radps = Eigen::Vector3d::Zero();  ///< bias-corrected rate, IMU frame
  /// state.t_ns − the last optimized state's time: how long the output has been IMU only.
  int64_t since_optimized_ns = 0;
};

struct ImuRateCounters {
  uint64_t samples = 0;           ///< accepted into the buffer
  uint64_t out_of_order = 0;      ///< dropped: not newer than the newest sample (incl. duplicates)
  uint64_t overflow_dropped = 0;  ///< oldest samples pushed out of a full buffer
  uint64_t before_state = 0;      ///< buffered without output: no state yet, or not newer than it
  uint64_t states = 0;            ///< optimized states applied
  uint64_t stale_states = 0;      ///< rejected: older than the previous optimized state
  uint64_t repropagated = 0;      ///< samples integrated again after a new state
};

class ImuRatePropagator {
 public:
  explicit ImuRatePropagator(const ImuRatePropagatorConfig& config);

  /// Takes a newly optimized state (time t_k, with biases) and re-propagates the buffered
  /// samples after t_k. Returns the current output (at the newest sample, or at t_k when no
  /// sample is newer); nullopt when the state is older than the previous one (counted).
  std::optional<ImuRateOutput> SetState(const State& optimized);

  /// Buffers one sample and integrates the current state to its time. Nullopt when the sample
  /// is out of order (dropped), or when there is no state yet or the state is newer (buffered).
  std::optional<ImuRateOutput> Add(const ImuSample& sample);

  /// Forgets the state and the buffered samples (the estimator restarted); counters are kept.
  void Clear();

  bool has_state() const { return has_state_; }
  size_t buffered() const { return size_; }
  const ImuRateCounters& counters() const { return counters_; }

 private:
  const ImuSample& At(size_t i) const { return ring_[(head_ + i) % ring_.size()]; }
  void Push(const ImuSample& sample);
  void DropUpTo(int64_t t_ns);
  /// The output at current_'s time (the re-basing offset applied and decayed); remembers it.
  ImuRateOutput Output(const ImuSample* newest);

  double gravity_mps2_;
  ImuRatePropagatorConfig config_;
  std::vector<ImuSample> ring_;  ///< fixed size: the buffer's capacity
  size_t head_ = 0;              ///< index of the oldest sample
  size_t size_ = 0;
  bool has_state_ = false;
  int64_t optimized_t_ns_ = 0;  ///< time of the last optimized state
  State current_;               ///< propagated to the newest integrated sample
  /// Output = current_ · rebase_ (body frame; re-basing not taken in yet); the last output and
  /// its time.
  Eigen::Isometry3d rebase_ = Eigen::Isometry3d::Identity();
  bool has_output_ = false;
  Eigen::Isometry3d last_output_ = Eigen::Isometry3d::Identity();
  int64_t last_output_t_ns_ = 0;
  ImuRateCounters counters_;
};

}  // namespace swlio::estimator

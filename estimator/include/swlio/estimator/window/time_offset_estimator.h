#pragma once
/// @file
/// Online LiDAR–IMU time offset, beside the window: the residual of the clock models that
/// neither sees (a USB-serial latency, the IMU's own filter delay).
///
/// Convention: `offset_s` = d > 0 means the IMU's stamps are d too late (the simulator's
/// `time_offset_s`: each sample measures the motion of d before its stamp), so the estimator
/// takes a sample stamped s as measured at s − d (Shifted).
///
/// Model: between two sweep ends t_a < t_b (LiDAR host time, span ≈ `span_s`) the sweeps' own
/// registrations give the rotation increment ΔR_L = R_aᵀ R_b of the IMU frame; the gyro
/// integrated over the stamps [t_a + d, t_b + d] with bias b gives ΔR_G(d, b). Each pair is one
/// residual r = Log(ΔR_Lᵀ ΔR_G(d, b)) (3 rows); ∂r/∂d ≈ ω(t_b) − ΔRᵀω(t_a), the change of rate
/// over the span, is what makes d observable (a constant turn or a straight line say nothing).
/// Jacobians by central differences of the integration (5 integrations of ~120 samples).
/// The last `history_s` of rows form a small least squares over [d, b_g] (4 unknowns, Huber
/// weights, two reweightings), each row kept at its own linearization point. Each row keeps
/// the offset applied when its registrations were made (its operating point): a registration
/// leans toward the IMU it was de-skewed and predicted with (measured 12–20 % of an unapplied
/// offset on `aggressive` 42), so rows of another operating point pull the estimate toward it.
/// The rows within `operating_point_tolerance_s` of the offset applied now are solved alone
/// first; once they pass the gate below, the others are dropped; until then all rows are solved
/// (a start, a walk: the estimate converges by iterating). At a settled operating point the
/// turns of the whole history are fused (a patrol's corners minutes apart), not replaced by the
/// last minute's. σ_d is the sandwich H⁻¹ S H⁻¹ (b_g marginalized), S the rows' scores with
/// their correlation over `correlated_rows` neighbours (Newey–West: rows share registrations
/// and gyro spans, a turn's registration errors run together), never below the σ of
/// independent rows scaled by the residuals' robust RMS. Beyond 300 rows a solve runs every
/// rows/300-th row. Only when σ_d ≤ `gate_sigma_s` (the motion constrains d), or when it is
/// ≤ `coarse_gate_sigma_s` and the estimate is over 3σ_d from the target, does the estimate
/// become the target, and the applied offset walks to it by at most `max_step_s` per sweep (the
/// IMU samples of the window stay in order and its factors change smoothly). Pure library: no
/// clock.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"

namespace swlio::estimator {

struct TimeOffsetConfig {
  /// Apply the offset to the IMU samples (off: the clock models' times as they are).
  bool enabled = true;
  /// Estimate it online (off: `initial_offset_s` stays, a known calibration).
  bool estimate = true;
  /// The offset to start from (s, the convention above): a calibration, or 0.
  double initial_offset_s = 0.0;
  /// Limit of the estimate (both signs): the clock models already remove the transport
  /// latency; what is left is a filter delay or a USB-serial latency of a few ms.
  double max_offset_s = 0.05;
  /// Rotation increments span about this much (pairs of sweep ends): the signal (the change of
  /// rate over the span) grows with it, the registration noise does not.
  double span_s = 0.3;
  double history_s = 300.0;  ///< rows kept (sliding): several corners of a patrol
  /// The estimate becomes the target only with σ_d at or below this (excitation gate) ...
  double gate_sigma_s = 4e-4;
  /// ... or, with σ_d at or below this, when it lies more than 3σ_d from the target: a start
  /// far off (10 ms) is then left sooner (8 s instead of 16–20 s into `aggressive`).
  double coarse_gate_sigma_s = 1.5e-3;
  size_t min_rows = 30;  ///< and at least this many rows
  /// The applied offset moves at most this much per sweep (10 ms/s at 10 Hz: a 10 ms start is
  /// applied within a second of passing the gate); below the IMU's 2.5 ms sample period, so
  /// shifted samples stay in order.
  double max_step_s = 1e-3;
  /// Huber width of a rotation residual (rad): 0.1° ≈ a sweep registration's jitter a few times.
  double huber_rad = 2e-3;
  /// Weight of the residual's roll/pitch rows against its yaw row (about the IMU's z axis).
  double tilt_weight = 1.0;
  /// Rows whose registrations were made at an applied offset within this of the one applied
  /// now are this operating point's; the others are dropped once these alone pass the gate. A
  /// registration leans toward the IMU it was de-skewed and predicted with (measured on
  /// `aggressive` 42 with 10 ms left unapplied: the estimate came out 12–20 % short).
  double operating_point_tolerance_s = 1e-3;
  /// σ_d from the rows' scores with their correlation over this many neighbours (Newey–West):
  /// rows share registrations and gyro spans (3 at span 0.3 s, 10 Hz) and a turn's
  /// registration errors run together.
  int correlated_rows = 10;
  /// How far the offset may be off before the first estimate (s, one σ; 0: off). The window's
  /// IMU factors carry the applied offset's uncertainty on their rotation (time_shift_jacobian.h)
  /// until it settles, so an IMU applied at the wrong time does not bend the window where its
  /// rates change. Measured (issue 36, bench/README "The field", five draws each): 10 ms brings
  /// `aggressive` 42 started 10 ms late from 1.18× to 1.02× the APE of the offset known (10 ms
  /// early: 1.19× → 1.23×) and costs `loop943` and `field` nothing; the earlier widening of
  /// velocity and position too cost the slow drives 3–22 %.
  double initial_sigma_s = 0.01;
  /// The window's own offset parameter, shared by its IMU factors (time_offset_imu_factor.h):
  /// free from this estimator's first gated estimate on, with a prior of this σ about that
  /// estimate (s; 0: off, the window takes the applied offset as exact). Off by default:
  /// measured (issue 36), it halves the misses of a start 5–10 ms off on `aggressive` but moves
  /// APE on slow drives by −34 … +45 % per seed, no better on average.
  double window_prior_sigma_s = 0.0;
  /// The window's IMU factors follow the estimate: each sweep every factor in the window is
  /// moved to first order (time_offset_imu_factor.h) from the offset its samples were shifted
  /// with to `followed_offset_s()`, and widened by `followed_sigma_s()` (before the first
  /// gated estimate: the applied offset and `applied_sigma_s()`, as without following, but
  /// taken by every factor in the window each sweep). The factors of a first turn's first sweeps,
  /// made before the gate passed, are then corrected while they are still in the window (0.5 s),
  /// not only the ones made after the walk. Measured (issue 36, bench/README "The field"):
  /// `aggressive` seed 1 started 10 ms off loses 0.2° of yaw in its first turn without it
  /// (APE 1.23× the offset known), 0.05° with it (1.01×).
  bool window_follows_estimate = true;

  ConfigIssues Validate() const;
};

/// What the daemon's health reports (WindowResult::time_offset).
struct TimeOffsetStatus {
  double offset_s = 0.0;    ///< applied to the IMU samples now (see the convention above)
  double estimate_s = 0.0;  ///< the last least-squares estimate (clamped to the limit)
  double sigma_s = -1.0;    ///< its standard deviation; negative until there are rows
  /// RMS over the rows of |∂r/∂d| (rad/s): how much the motion constrains d.
  double excitation_radps = 0.0;
  double residual_rms_rad = 0.0;  ///< robust RMS of the rotation residuals
  size_t rows = 0;                ///< rotation increments in the history
  size_t updates = 0;             ///< sweeps so far at which the gate passed
  bool enabled = false;
  bool gated = false;  ///< the last solve passed the gate (the estimate is the target)
  /// The window's own offset parameter (window_prior_sigma_s), where it is estimated.
  std::optional<double> window_offset_s;
};

class TimeOffsetEstimator {
 public:
  explicit TimeOffsetEstimator(const TimeOffsetConfig& config);

  /// A sample as stamped (the clock model's host time); kept for the gyro integrations.
  void AddImu(const ImuSample& sample);
  /// The sample at the time it measured: its stamp minus the applied offset.
  ImuSample Shifted(ImuSample sample) const;
  /// A sweep's own registration (IMU attitude at the sweep end `t_ns`, LiDAR host time). Forms
  /// the rows its IMU coverage allows, solves, and moves the applied offset.
  void AddRegistration(int64_t t_ns, const Eigen::Quaterniond& q_world_imu);
  /// Forgets rows and registrations (a re-initialization); the offset and samples are kept.
  void ForgetRows();

  int64_t offset_ns() const { return offset_ns_; }
  /// How far the applied offset may be from the truth (s, one σ): 0 when it is not estimated
  /// (a known calibration) or `initial_sigma_s` is 0. Before the first gated estimate, what the
  /// rows say so far (the fit's σ together with its distance from the applied offset, once
  /// `min_rows` are in), never more than `initial_sigma_s`: a slow drive narrows it long before
  /// the gate passes. Afterwards the last gated estimate's σ together with the walk still to go.
  double applied_sigma_s() const;
  const TimeOffsetStatus& status() const { return status_; }
  /// Where the window's factors are moved to (window_follows_estimate): the last gated
  /// estimate; before it the applied offset. (The rows' estimate before the gate, followed too,
  /// moved the start of `aggressive` seed 42: 1.26× the APE of the offset known at −10 ms.)
  double followed_offset_s() const;
  /// Its σ: the gated estimate's; before it `applied_sigma_s()`, as without following
  /// (`initial_sigma_s` there instead cost
  /// `field` seed 2 13–19 %: its sweeps diverged from 30 s on, its gate passing at 62 s).
  /// 0 where the offset is not estimated or `initial_sigma_s` is 0.
  double followed_sigma_s() const;

  /// Gyro rotation over stamps [a_ns, b_ns] with `bias` removed: each sample's mean rate over
  /// its interval (core/types.h). Empty unless the samples cover [a_ns, b_ns].
  static std::optional<Eigen::Quaterniond> IntegrateGyro(const std::deque<ImuSample>& samples,
                                                         int64_t a_ns,
                                                         int64_t b_ns,
                                                         const Eigen::Vector3d& bias);

 private:
  struct Registration {
    int64_t t_ns;
    int64_t applied_ns;  ///< the offset applied when the sweep was de-skewed and registered
    Eigen::Quaterniond q_world_imu;
  };
  struct Row {
    int64_t t_ns;
    int64_t applied_ns;             ///< its registrations' applied offset (operating point)
    Eigen::Matrix<double, 3, 4> J;  ///< ∂r/∂[d, b_g]
    Eigen::Vector3d r;              ///< at x_lin
    Eigen::Vector4d x_lin;          ///< [d (s), b_g (rad/s)]
  };
  void FormRows();
  std::optional<Row> MakeRow(const Registration& a, const Registration& b) const;
  /// One robust least squares over the rows (or those of this operating point only).
  struct Fit {
    Eigen::Vector4d x = Eigen::Vector4d::Zero();  ///< [d, b_g]
    double sigma_s = 1e3;
    double rms_rad = 0.0;
    double excitation_radps = 0.0;
    size_t rows = 0;
  };
  /// A row's residual and Jacobian at x, roll/pitch rows scaled by `tilt_weight`, and its Huber
  /// weight: what the fit and the score covariance both use.
  struct WeightedRow {
    Eigen::Vector3d e;
    Eigen::Matrix<double, 3, 4> J;
    double w = 1.0;
  };
  WeightedRow Weigh(const Row& row, const Eigen::Vector4d& x) const;
  bool AtThisOperatingPoint(const Row& row) const;
  void Solve();
  Fit FitRows(bool this_operating_point_only);
  /// Σ_k Σ_l s_k s_lᵀ of the rows' scores s = w Jᵀe at `x`, over lags up to `correlated_rows`.
  Eigen::Matrix4d CorrelatedScoreCovariance(const Eigen::Vector4d& x,
                                            bool this_operating_point_only);
  void Step();

  TimeOffsetConfig config_;
  std::deque<ImuSample> imu_;               ///< stamps as received, the last seconds
  std::deque<Registration> registrations_;  ///< waiting to be the end or start of a row
  std::deque<Row> rows_;
  std::vector<Eigen::Vector4d> scores_;          ///< reused by CorrelatedScoreCovariance
  Eigen::Vector4d x_ = Eigen::Vector4d::Zero();  ///< [d, b_g], the last solution
  double target_s_;                              ///< the last estimate that passed the gate
  double gated_sigma_s_ = 0.0;                   ///< σ of that estimate
  int64_t offset_ns_;
  bool pending_end_ = false;  ///< the newest registration has not ended a row yet
  size_t rows_since_solve_ = 0;
  TimeOffsetStatus status_;
};

}  // namespace swlio::estimator

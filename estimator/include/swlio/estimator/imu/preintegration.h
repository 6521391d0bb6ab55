#pragma once
/// @file
/// IMU pre-integration on the manifold between two times (Forster, Carlone, Dellaert,
/// Scaramuzza, "On-Manifold Preintegration for Real-Time Visual-Inertial Odometry", IEEE TRO
/// 2017; equation numbers below refer to that paper).
///
/// Relative motion terms (§V-A), expressed in the IMU frame at the interval start i:
///   ΔR_ij = Π_k Exp((ω̃_k − b_g) Δt)
///   Δv_ij = Σ_k ΔR_ik (ã_k − b_a) Δt
///   Δp_ij = Σ_k [Δv_ik Δt + ½ ΔR_ik (ã_k − b_a) Δt²]
/// They depend only on the measurements and the linearization bias b̄ = (b̄_g, b̄_a).
///
/// Integration scheme (stated once): INTERVAL MEANS. A sample holds the mean rate and specific
/// force over the interval since the previous sample (core/types.h), so the step from sample k
/// to sample k+1 takes sample k+1's values, ω̄ = ω̃_{k+1}, ā = ã_{k+1}, and rotates the
/// specific force with the attitude at the step's middle, ΔR_mid = ΔR_ik Exp(½ θ_k),
/// θ_k = (ω̄ − b_g) Δt. The rotation is then the device's own integral, and the velocity and
/// position are exact up to the specific force's turn within a step: motion faster than the
/// sample rate (vibration) integrates as the device measured it, where averaging two samples
/// (the midpoint rule for instantaneous samples) filters it out. A step cut by an interval
/// bound takes the mean over its part of the sample's interval, from the line through the
/// neighbouring samples' means held to the sample's own (MeanOverPart): the sample's whole mean
/// there is off by about ½ ȧ τ (T − τ) over the part τ of its interval T, which on a vibrating
/// chassis is several times the white noise's share of an interval (issue 36; the two parts of
/// one sample still sum to its mean, so consecutive intervals keep the device's integral).
/// The noise and bias Jacobian recursions (derived in preintegration.cpp) are the exact
/// linearization of this scheme, checked against central differences in the tests.
///
/// Error state (9): [δφ; δv; δp] with ΔR̃ = ΔR Exp(δφ), Δṽ = Δv + δv, Δp̃ = Δp + δp (§V-B).
/// Bias Jacobian J (9×6): rows [φ; v; p], columns [b_g; b_a]; first-order bias update (eq. (44)):
///   ΔR(b) = ΔR(b̄) Exp(J_R_bg δb_g),  Δv(b) = Δv(b̄) + J_v_bg δb_g + J_v_ba δb_a,
///   Δp(b) = Δp(b̄) + J_p_bg δb_g + J_p_ba δb_a.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/estimator/common/estimator_config.h"

namespace swlio::estimator {

using Mat9 = Eigen::Matrix<double, 9, 9>;
using Mat96 = Eigen::Matrix<double, 9, 6>;
using Vec9 = Eigen::Matrix<double, 9, 1>;

/// Rows of the 9-dimensional error state and of the residual.
inline constexpr int kRowR = 0;
inline constexpr int kRowV = 3;
inline constexpr int kRowP = 6;
/// Columns of the bias Jacobian.
inline constexpr int kColBg = 0;
inline constexpr int kColBa = 3;

/// Pre-integrated measurement between t_start_ns and t_end_ns.
struct PreintegratedImu {
  int64_t t_start_ns = 0;
  int64_t t_end_ns = 0;
  double dt_s = 0.0;  ///< Δt_ij
  Eigen::Matrix3d delta_R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d delta_v = Eigen::Vector3d::Zero();
  Eigen::Vector3d delta_p = Eigen::Vector3d::Zero();
  Mat9 covariance = Mat9::Zero();  ///< of [δφ; δv; δp], from the measurement white noise
  Mat96 jacobian_bias = Mat96::Zero();
  Eigen::Vector3d bias_gyro_lin = Eigen::Vector3d::Zero();  ///< b̄_g used to integrate
  Eigen::Vector3d bias_acc_lin = Eigen::Vector3d::Zero();   ///< b̄_a used to integrate

  Eigen::Matrix3d J_R_bg() const { return jacobian_bias.block<3, 3>(kRowR, kColBg); }
  Eigen::Matrix3d J_v_bg() const { return jacobian_bias.block<3, 3>(kRowV, kColBg); }
  Eigen::Matrix3d J_v_ba() const { return jacobian_bias.block<3, 3>(kRowV, kColBa); }
  Eigen::Matrix3d J_p_bg() const { return jacobian_bias.block<3, 3>(kRowP, kColBg); }
  Eigen::Matrix3d J_p_ba() const { return jacobian_bias.block<3, 3>(kRowP, kColBa); }
};

/// The three relative-motion terms after a first-order bias update.
struct CorrectedDeltas {
  Eigen::Matrix3d delta_R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d delta_v = Eigen::Vector3d::Zero();
  Eigen::Vector3d delta_p = Eigen::Vector3d::Zero();
};

/// First-order bias update, eq. (44): the terms for the biases (bias_gyro, bias_acc) without
/// re-integration.
CorrectedDeltas Corrected(const PreintegratedImu& pim,
                          const Eigen::Vector3d& bias_gyro,
                          const Eigen::Vector3d& bias_acc);

/// Covariance (6×6, [b_g; b_a]) of the bias random walk over the interval (Forster §V, bias model):
/// diag(σ_bg² Δt I, σ_ba² Δt I) with σ the continuous random-walk densities.
Eigen::Matrix<double, 6, 6> BiasWalkCovariance(const ImuNoiseConfig& noise, double dt_s);

enum class PreintegrationStatus {
  kOk,
  kNotCovered,    ///< the samples do not span [t_start_ns, t_end_ns]
  kBadInterval,   ///< t_end_ns < t_start_ns
  kUnsortedTime,  ///< sample times go backwards
};

/// Accumulates samples into a PreintegratedImu. Not thread-safe; cheap to copy.
class Preintegrator {
 public:
  struct Options {
    /// Re-integrate (rather than correct to first order) when |δb_g| exceeds this (rad/s)…
    double reintegrate_gyro_bias_radps = 0.01;
    /// …or |δb_a| exceeds this (m/s²).
    double reintegrate_acc_bias_mps2 = 0.2;
    /// Keep the integrated samples so that Reintegrate() works (costs a copy).
    bool keep_samples = true;
  };

  Preintegrator(const ImuNoiseConfig& noise,
                const Eigen::Vector3d& bias_gyro,
                const Eigen::Vector3d& bias_acc);
  Preintegrator(const ImuNoiseConfig& noise,
                const Eigen::Vector3d& bias_gyro,
                const Eigen::Vector3d& bias_acc,
                const Options& options);

  /// Starts an empty interval at t_ns with new linearization biases.
  void Reset(int64_t t_ns, const Eigen::Vector3d& bias_gyro, const Eigen::Vector3d& bias_acc);

  /// Integrates one step from sample a's time to sample b's with b's values (b.t_ns ≥ a.t_ns;
  /// a.t_ns should be the current end of the interval). Streaming use: consecutive samples.
  void IntegrateStep(const ImuSample& a, const ImuSample& b);

  /// Resets at t_start_ns and integrates `samples` (sorted by time) over [t_start, t_end]. The
  /// samples must bracket both bounds; the steps cut by a bound take the mean over their part of
  /// the interval of the sample that holds them (MeanOverPart: with a sample before and after
  /// that one; else its whole mean).
  PreintegrationStatus Integrate(std::span<const ImuSample> samples,
                                 int64_t t_start_ns,
                                 int64_t t_end_ns);

  /// True when the bias change from the linearization point is too large for eq. (44).
  bool NeedsReintegration(const Eigen::Vector3d& bias_gyro, const Eigen::Vector3d& bias_acc) const;

  /// Integrates the kept samples again with new biases (requires Options::keep_samples; works
  /// after Integrate() and after streaming IntegrateStep() calls).
  void Reintegrate(const Eigen::Vector3d& bias_gyro, const Eigen::Vector3d& bias_acc);

  /// The terms for new biases: first-order correction, or re-integration if the change is
  /// large (NeedsReintegration), in which case the stored result is replaced.
  CorrectedDeltas UpdateBias(const Eigen::Vector3d& bias_gyro, const Eigen::Vector3d& bias_acc);

  const PreintegratedImu& result() const { return pim_; }
  const ImuNoiseConfig& noise() const { return noise_; }

 private:
  void Propagate(const ImuSample& a, const ImuSample& b);  ///< the maths of one step

  ImuNoiseConfig noise_;
  Options options_;
  PreintegratedImu pim_;
  std::vector<ImuSample> samples_;  ///< the interval's samples, the cut bounds' restamped
};

/// The values that hold at t_ns: those of the first sample at or after it (its interval holds
/// t_ns), restamped t_ns. `samples` sorted by time, the last at or after t_ns.
ImuSample SampleHolding(std::span<const ImuSample> samples, int64_t t_ns);

/// Sample h's values over [lo_ns, hi_ns], a part of its interval (samples[h − 1].t_ns,
/// samples[h].t_ns], stamped hi_ns: its mean moved along the line through the means of samples
/// h − 1 and h + 1 (a central difference, each mean at its interval's middle) to the part's
/// middle. Its whole mean where a neighbour is missing or the three are unevenly spaced (over
/// 3:2, a gap). Against a tone of 15 / 80 Hz sampled at 400 Hz it leaves 2 % / 28 % of the
/// whole mean's error over a part (RMS over phases and cuts).
ImuSample MeanOverPart(std::span<const ImuSample> samples, size_t h, int64_t lo_ns, int64_t hi_ns);

}  // namespace swlio::estimator

#include "swlio/estimator/imu/preintegration.h"

#include <algorithm>
#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

/// X ← A X for the step's A = [Eᵀ 0 0; M I 0; N Δt·I I] (block rows φ, v, p), exploiting the
/// structure: 3 block products per column block instead of a dense 9×9 product.
template <int Cols>
void ApplyA(
    const Mat3& Et, const Mat3& M, const Mat3& N, double dt, Eigen::Matrix<double, 9, Cols>& X) {
  const Eigen::Matrix<double, 3, Cols> X_r = X.template middleRows<3>(kRowR);
  X.template middleRows<3>(kRowP) += dt * X.template middleRows<3>(kRowV) + N * X_r;
  X.template middleRows<3>(kRowV) += M * X_r;
  X.template middleRows<3>(kRowR) = Et * X_r;
}

}  // namespace

ImuSample SampleHolding(std::span<const ImuSample> samples, int64_t t_ns) {
  const auto it = std::lower_bound(samples.begin(), samples.end(), t_ns,
                                   [](const ImuSample& s, int64_t t) { return s.t_ns < t; });
  ImuSample out = it == samples.end() ? samples.back() : *it;
  out.t_ns = t_ns;
  return out;
}

ImuSample MeanOverPart(std::span<const ImuSample> samples, size_t h, int64_t lo_ns, int64_t hi_ns) {
  ImuSample out = samples[h];
  out.t_ns = hi_ns;
  if (h == 0 || h + 1 >= samples.size()) return out;  // no neighbour on one side: its mean
  const ImuSample& before = samples[h - 1];
  const ImuSample& after = samples[h + 1];
  const int64_t own_ns = samples[h].t_ns - before.t_ns;
  const int64_t next_ns = after.t_ns - samples[h].t_ns;
  // Uneven spacing (a gap, a synthetic bound): the neighbours are no line's samples.
  if (own_ns <= 0 || next_ns <= 0 || 2 * std::max(own_ns, next_ns) > 3 * std::min(own_ns, next_ns))
    return out;
  // The line through the neighbours' means (at their intervals' middles, 2T apart), held to this
  // sample's mean: a(t) = m + g (t − c), c the middle of its interval.
  const double span_s = NsToSec(after.t_ns - before.t_ns);
  const double from_middle_s =
      0.5 * NsToSec((lo_ns - before.t_ns) + (hi_ns - samples[h].t_ns));  // (lo + hi)/2 − c
  out.gyro_radps += (after.gyro_radps - before.gyro_radps) * (from_middle_s / span_s);
  out.acc_mps2 += (after.acc_mps2 - before.acc_mps2) * (from_middle_s / span_s);
  return out;
}

CorrectedDeltas Corrected(const PreintegratedImu& pim,
                          const Vec3& bias_gyro,
                          const Vec3& bias_acc) {
  // Forster eq. (44): first-order expansion around the linearization bias b̄.
  const Vec3 dbg = bias_gyro - pim.bias_gyro_lin;
  const Vec3 dba = bias_acc - pim.bias_acc_lin;
  CorrectedDeltas c;
  c.delta_R = pim.delta_R * lie::Exp(pim.J_R_bg() * dbg);
  c.delta_v = pim.delta_v + pim.J_v_bg() * dbg + pim.J_v_ba() * dba;
  c.delta_p = pim.delta_p + pim.J_p_bg() * dbg + pim.J_p_ba() * dba;
  return c;
}

Eigen::Matrix<double, 6, 6> BiasWalkCovariance(const ImuNoiseConfig& noise, double dt_s) {
  // Bias as a Wiener process ḃ = η_b: over Δt its increment has covariance σ_b² Δt I.
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  const double sg = noise.gyro_bias_random_walk_radps2_per_sqrthz;
  const double sa = noise.acc_bias_random_walk_mps3_per_sqrthz;
  c.diagonal().head<3>().setConstant(sg * sg * dt_s);
  c.diagonal().tail<3>().setConstant(sa * sa * dt_s);
  return c;
}

Preintegrator::Preintegrator(const ImuNoiseConfig& noise,
                             const Vec3& bias_gyro,
                             const Vec3& bias_acc)
    : Preintegrator(noise, bias_gyro, bias_acc, Options{}) {}

Preintegrator::Preintegrator(const ImuNoiseConfig& noise,
                             const Vec3& bias_gyro,
                             const Vec3& bias_acc,
                             const Options& options)
    : noise_(noise), options_(options) {
  Reset(0, bias_gyro, bias_acc);
}

void Preintegrator::Reset(int64_t t_ns, const Vec3& bias_gyro, const Vec3& bias_acc) {
  pim_ = PreintegratedImu{};
  pim_.t_start_ns = t_ns;
  pim_.t_end_ns = t_ns;
  pim_.bias_gyro_lin = bias_gyro;
  pim_.bias_acc_lin = bias_acc;
  samples_.clear();
}

// One step from sample a to sample b, with b's interval means ω̄, ā (preintegration.h),
// θ = (ω̄ − b_g)Δt, a = ā − b_a, E = Exp(θ), H = Exp(½θ),
// R_m = ΔR_k H (attitude at the step's middle):
//   ΔR_{k+1} = ΔR_k E
//   Δv_{k+1} = Δv_k + R_m a Δt
//   Δp_{k+1} = Δp_k + Δv_k Δt + ½ R_m a Δt²
// Linearization (right perturbations, Forster §V-B and Appendix A, adapted to the midpoint):
// a perturbation η of the rate (white noise, or −δb_g) gives
//   Exp(θ + ηΔt) ≈ E Exp(Jr(θ) ηΔt),  Exp(½(θ + ηΔt)) ≈ H Exp(½ Jr(½θ) ηΔt), so
//   δφ_{k+1} = Eᵀ δφ_k + Jr(θ)Δt η_g
//   δφ_m     = Hᵀ δφ_k + ½ Jr(½θ)Δt η_g          (error of R_m)
//   δv_{k+1} = δv_k − R_m [a]× Δt δφ_m + R_m Δt η_a
//   δp_{k+1} = δp_k + Δt δv_k − ½ R_m [a]× Δt² δφ_m + ½ R_m Δt² η_a
// i.e. δ_{k+1} = A δ_k + B η with the 9×9 A and 9×6 B below. Then
//   covariance:     Σ_{k+1} = A Σ_k Aᵀ + B Q Bᵀ, Q = diag(σ_g² I, σ_a² I), σ² = density²/Δt
//                   (the noise of a sample averaged over Δt, Forster §IV: Cov(η_d) =
//                   Cov(η)/Δt), plus σ_a² Δt³/12 I on δp: white acceleration noise integrated
//                   exactly over the step gives Cov(δp) = σ_a² Δt³/3 where B Q Bᵀ gives
//                   σ_a² Δt³/4 (Cov(δp, δv) = σ_a² Δt²/2 and Cov(δv) = σ_a² Δt agree). The
//                   difference is ~1/(4N²) of an N-step interval's δp covariance, but without
//                   it a one-step interval's δp and δv are perfectly correlated and Σ is
//                   singular: a sweep inside an IMU gap, bridged by one interpolated step, got
//                   no IMU factor, and its velocity and biases fell to the bias prior's zero;
//   bias Jacobians: a bias change δb acts like η = −δb, so J_{k+1} = A J_k − B.
void Preintegrator::IntegrateStep(const ImuSample& a, const ImuSample& b) {
  if (options_.keep_samples) {
    if (samples_.empty()) samples_.push_back(a);
    samples_.push_back(b);
  }
  Propagate(a, b);
}

void Preintegrator::Propagate(const ImuSample& a, const ImuSample& b) {
  const double dt = NsToSec(b.t_ns - a.t_ns);
  pim_.t_end_ns = b.t_ns;
  if (dt <= 0.0) return;
  const Vec3 theta = (b.gyro_radps - pim_.bias_gyro_lin) * dt;  // b's interval holds the step
  const Vec3 acc = b.acc_mps2 - pim_.bias_acc_lin;
  const Mat3 E = lie::Exp(theta);
  const Mat3 H = lie::Exp(0.5 * theta);
  const Mat3 R_mid = pim_.delta_R * H;
  const Mat3 Rm_acc_hat = R_mid * lie::Hat(acc);
  const double dt2 = dt * dt;

  const Mat3 Et = E.transpose();
  const Mat3 M = -Rm_acc_hat * H.transpose() * dt;  // A_vφ
  const Mat3 N = 0.5 * dt * M;                      // A_pφ

  const Mat3 half_jr_dt = 0.5 * lie::RightJacobian(0.5 * theta) * dt;
  Mat96 B = Mat96::Zero();
  B.block<3, 3>(kRowR, kColBg) = lie::RightJacobian(theta) * dt;
  B.block<3, 3>(kRowV, kColBg) = -Rm_acc_hat * half_jr_dt * dt;
  B.block<3, 3>(kRowV, kColBa) = R_mid * dt;
  B.block<3, 3>(kRowP, kColBg) = -0.5 * Rm_acc_hat * half_jr_dt * dt2;
  B.block<3, 3>(kRowP, kColBa) = 0.5 * R_mid * dt2;

  const double ng = noise_.gyro_noise_density_radps_per_sqrthz;
  const double na = noise_.acc_noise_density_mps2_per_sqrthz;
  Eigen::Matrix<double, 6, 1> q;
  q << Vec3::Constant(ng * ng / dt), Vec3::Constant(na * na / dt);

  // Σ ← A Σ Aᵀ = A (A Σ)ᵀ (Σ symmetric), then + B Q Bᵀ.
  Mat9& cov = pim_.covariance;
  ApplyA(Et, M, N, dt, cov);
  cov.transposeInPlace();
  ApplyA(Et, M, N, dt, cov);
  cov.noalias() += B * q.asDiagonal() * B.transpose();
  cov.block<3, 3>(kRowP, kRowP).diagonal().array() += na * na * dt2 * dt / 12.0;
  cov = 0.5 * (cov + cov.transpose()).eval();
  ApplyA(Et, M, N, dt, pim_.jacobian_bias);
  pim_.jacobian_bias -= B;

  // The means, last: the linearization above uses ΔR_k, Δv_k.
  pim_.delta_p += pim_.delta_v * dt + 0.5 * R_mid * acc * dt2;
  pim_.delta_v += R_mid * acc * dt;
  pim_.delta_R = pim_.delta_R * E;
  pim_.dt_s += dt;
}

PreintegrationStatus Preintegrator::Integrate(std::span<const ImuSample> samples,
                                              int64_t t_start_ns,
                                              int64_t t_end_ns) {
  const Vec3 bias_gyro = pim_.bias_gyro_lin;  // copies: Reset() clears pim_
  const Vec3 bias_acc = pim_.bias_acc_lin;
  Reset(t_start_ns, bias_gyro, bias_acc);
  if (t_end_ns < t_start_ns) return PreintegrationStatus::kBadInterval;
  for (size_t k = 1; k < samples.size(); ++k) {
    if (samples[k].t_ns < samples[k - 1].t_ns) return PreintegrationStatus::kUnsortedTime;
  }
  if (samples.empty() || samples.front().t_ns > t_start_ns || samples.back().t_ns < t_end_ns) {
    return PreintegrationStatus::kNotCovered;
  }
  // Last sample at or before the start, first sample at or after the end.
  size_t first = 0;
  while (first + 1 < samples.size() && samples[first + 1].t_ns <= t_start_ns) ++first;
  size_t last = first;
  while (samples[last].t_ns < t_end_ns) ++last;

  // The steps cut by a bound take the mean over their part of the sample's interval.
  ImuSample prev = SampleHolding(samples, t_start_ns);
  if (options_.keep_samples) samples_.reserve(last - first + 2);
  for (size_t k = first + 1; k < last; ++k) {
    IntegrateStep(
        prev, k == first + 1 ? MeanOverPart(samples, k, t_start_ns, samples[k].t_ns) : samples[k]);
    prev = samples[k];
  }
  IntegrateStep(prev, MeanOverPart(samples, last, prev.t_ns, t_end_ns));
  return PreintegrationStatus::kOk;
}

bool Preintegrator::NeedsReintegration(const Vec3& bias_gyro, const Vec3& bias_acc) const {
  return (bias_gyro - pim_.bias_gyro_lin).norm() > options_.reintegrate_gyro_bias_radps ||
         (bias_acc - pim_.bias_acc_lin).norm() > options_.reintegrate_acc_bias_mps2;
}

void Preintegrator::Reintegrate(const Vec3& bias_gyro, const Vec3& bias_acc) {
  if (samples_.size() < 2) return;  // nothing kept: the caller must integrate again
  std::vector<ImuSample> kept;
  kept.swap(samples_);
  Reset(pim_.t_start_ns, bias_gyro, bias_acc);
  for (size_t k = 1; k < kept.size(); ++k) Propagate(kept[k - 1], kept[k]);
  samples_.swap(kept);
}

CorrectedDeltas Preintegrator::UpdateBias(const Vec3& bias_gyro, const Vec3& bias_acc) {
  if (NeedsReintegration(bias_gyro, bias_acc) && samples_.size() >= 2) {
    Reintegrate(bias_gyro, bias_acc);
  }
  return Corrected(pim_, bias_gyro, bias_acc);
}

}  // namespace swlio::estimator

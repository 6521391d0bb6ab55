#pragma once
/// @file
/// How a pre-integrated interval changes when its samples' times are all off by the same ε
/// (an error in the LiDAR–IMU time offset applied to them): the deltas then describe the
/// motion over [t_i + ε, t_j + ε] instead of [t_i, t_j]. To first order, in the error state
/// of preintegration.h ([δφ; δv; δp], ΔR̃ = ΔR Exp(δφ), frame i), with ω and a the
/// bias-corrected rate and specific force at the interval's ends:
///   δφ = (ω_j − ΔRᵀ ω_i) ε
///   δv = (ΔR a_j − a_i − ω_i × Δv) ε
///   δp = (Δv − a_i Δt − ω_i × Δp) ε
/// (differentiating the integrals' limits and the start frame R(t_i + ε) = R_i Exp(ω_i ε)).
/// An offset known to σ_d then widens the interval's rotation by σ_d² J_φ J_φᵀ (J_φ the δφ rows):
/// a factor made while the offset is unsettled does not pull the window's attitude with the
/// error it carries. The δv and δp rows are left as they are. They hold the specific force at
/// the interval's two ends, and on a vibrating chassis or over a bump that changes by 1–2 m/s²
/// from one end to the other. Widened factor by factor, each interval would then lose most of
/// its velocity information, although a shift of all samples moves a chain of intervals by the
/// telescoping (a_last − a_first) ε alone. Measured (issue 36, bench/README "The field"): with
/// 10 ms of initial uncertainty, the full widening cost the slow drives 3–22 %; the rotation's
/// alone costs them nothing and brings `aggressive` 42 started 10 ms late from 1.18× to 1.02×
/// the APE of the offset known (10 ms early: 1.19× → 1.23×).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {

/// ∂[δφ; δv; δp]/∂ε (per second) of `pim`, with `first` and `last` the rate and specific force
/// at its start and end (EndRates: one raw sample's white noise would enter J).
Vec9 TimeShiftJacobian(const PreintegratedImu& pim, const ImuSample& first, const ImuSample& last);

/// The span EndRates fits over: 16 samples of a 400 Hz IMU.
inline constexpr int64_t kEndRatesSpanNs = 40'000'000;

/// The rate and specific force at `t_ns` (stamped so), from a straight line fitted by least
/// squares to the samples (sorted by time) within `span_ns` of it, each at the middle of its
/// interval (core/types.h); the nearest sample where fewer than three are. J from raw samples
/// carries their white noise: at 400 Hz one sample's variance is the noise density² · 400 Hz, and
/// σ_d² J Jᵀ then doubles a 0.1 s interval's covariance at σ_d = 10 ms on a drive whose motion
/// hardly changes. The line's end keeps a steady change of the motion unbiased and has about a
/// quarter of one sample's variance ((4n − 2) / (n (n + 1)) for n samples).
ImuSample EndRates(const std::vector<ImuSample>& samples,
                   int64_t t_ns,
                   int64_t span_ns = kEndRatesSpanNs);

/// `pim` with σ_d² J_φ J_φᵀ added to its rotation block (J_φ: the δφ rows of J = TimeShiftJacobian;
/// the header says why only those).
PreintegratedImu WithTimeOffsetUncertainty(PreintegratedImu pim, const Vec9& J, double sigma_s);

}  // namespace swlio::estimator

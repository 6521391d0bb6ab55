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
/// An offset known to σ_d then adds σ_d² J Jᵀ to the interval's covariance: a factor made while
/// the offset is unsettled does not pull the window with the error it carries.

#include <Eigen/Core>

#include "swlio/core/types.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {

/// ∂[δφ; δv; δp]/∂ε (per second) of `pim`, whose first and last samples are `first` and `last`.
Vec9 TimeShiftJacobian(const PreintegratedImu& pim, const ImuSample& first, const ImuSample& last);

/// `pim` with σ_d² J Jᵀ added to its covariance (J = TimeShiftJacobian).
PreintegratedImu WithTimeOffsetUncertainty(PreintegratedImu pim, const Vec9& J, double sigma_s);

}  // namespace swlio::estimator

#pragma once
/// @file
/// An IMU factor (ImuFactor or GravityTiltImuFactor) whose samples were placed with a LiDAR–IMU
/// time offset that may be wrong: the offset d (s, time_offset_estimator.h's convention) is one
/// more parameter block, shared by every IMU factor of the window (as VINS-Mono's t_d,
/// Qin & Shen, "Online Temporal Calibration for Monocular Visual-Inertial Systems", IROS 2018).
///
/// The interval's samples were shifted by the offset applied then, d_a. With the offset d, they
/// measured the motion over [t_i − ε, t_j − ε], ε = d − d_a, so to first order the deltas of
/// [t_i, t_j] are Δ + J ε (J = TimeShiftJacobian) and the residual rows, which subtract Δ,
///   r(d) = r − W [J; 0] (d − d_a)            (W the factor's square-root information).
/// A shift telescopes along the chain (ω_j − ω_i of neighbouring intervals cancel), so one
/// shared d costs the window one unknown, where widening each factor on its own would cost it
/// the rates' information in every interval.
///
/// Parameter blocks: the inner factor's, then d[1]. The inner factor is not owned.

#include <ceres/cost_function.h>

#include <Eigen/Core>

#include "swlio/core/types.h"
#include "swlio/estimator/imu/imu_factor.h"

namespace swlio::estimator {

class TimeOffsetImuFactor final : public ceres::CostFunction {
 public:
  /// `inner`'s residual is `imu`'s (the same rows and whitening); `applied_offset_s` is d_a.
  TimeOffsetImuFactor(const ceres::CostFunction* inner,
                      const ImuFactor& imu,
                      const Vec9& time_shift_jacobian,
                      double applied_offset_s);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  const ceres::CostFunction* inner_;
  Eigen::Matrix<double, kImuFactorResiduals, 1> dr_dd_;  ///< −W [J; 0]
  double applied_offset_s_;
};

}  // namespace swlio::estimator

#include "swlio/estimator/imu/time_offset_imu_factor.h"

namespace swlio::estimator {

TimeOffsetImuFactor::TimeOffsetImuFactor(const ceres::CostFunction* inner,
                                         const ImuFactor& imu,
                                         const Vec9& time_shift_jacobian,
                                         double applied_offset_s)
    : inner_(inner),
      dr_dd_(-imu.sqrt_information().leftCols<9>() * time_shift_jacobian),
      applied_offset_s_(applied_offset_s) {
  *mutable_parameter_block_sizes() = inner->parameter_block_sizes();
  mutable_parameter_block_sizes()->push_back(1);
  set_num_residuals(kImuFactorResiduals);
}

bool TimeOffsetImuFactor::Evaluate(double const* const* parameters,
                                   double* residuals,
                                   double** jacobians) const {
  if (!inner_->Evaluate(parameters, residuals, jacobians)) return false;
  const size_t d_block = inner_->parameter_block_sizes().size();
  const double eps_s = parameters[d_block][0] - applied_offset_s_;
  Eigen::Map<Eigen::Matrix<double, kImuFactorResiduals, 1>>{residuals} += dr_dd_ * eps_s;
  if (jacobians != nullptr && jacobians[d_block] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, kImuFactorResiduals, 1>>{jacobians[d_block]} = dr_dd_;
  }
  return true;
}

}  // namespace swlio::estimator

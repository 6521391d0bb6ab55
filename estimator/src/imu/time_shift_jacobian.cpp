#include "swlio/estimator/imu/time_shift_jacobian.h"

namespace swlio::estimator {

Vec9 TimeShiftJacobian(const PreintegratedImu& pim, const ImuSample& first, const ImuSample& last) {
  const Eigen::Vector3d w_i = first.gyro_radps - pim.bias_gyro_lin;
  const Eigen::Vector3d w_j = last.gyro_radps - pim.bias_gyro_lin;
  const Eigen::Vector3d a_i = first.acc_mps2 - pim.bias_acc_lin;
  const Eigen::Vector3d a_j = last.acc_mps2 - pim.bias_acc_lin;
  Vec9 J;
  J.segment<3>(kRowR) = w_j - pim.delta_R.transpose() * w_i;
  J.segment<3>(kRowV) = pim.delta_R * a_j - a_i - w_i.cross(pim.delta_v);
  J.segment<3>(kRowP) = pim.delta_v - a_i * pim.dt_s - w_i.cross(pim.delta_p);
  return J;
}

PreintegratedImu WithTimeOffsetUncertainty(PreintegratedImu pim, const Vec9& J, double sigma_s) {
  if (sigma_s > 0.0) pim.covariance += (sigma_s * sigma_s) * J * J.transpose();
  return pim;
}

}  // namespace swlio::estimator

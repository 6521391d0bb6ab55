#include "swlio/estimator/imu/time_shift_jacobian.h"

#include <cmath>
#include <cstdlib>

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

ImuSample EndRates(const std::vector<ImuSample>& samples, int64_t t_ns, int64_t span_ns) {
  ImuSample out;
  out.t_ns = t_ns;
  if (samples.empty()) return out;
  // Sums for the line x(t) = x̄ + β (t − t̄), t in seconds from t_ns.
  double n = 0.0, sum_t = 0.0, sum_tt = 0.0;
  Eigen::Vector3d sum_w = Eigen::Vector3d::Zero(), sum_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_tw = Eigen::Vector3d::Zero(), sum_ta = Eigen::Vector3d::Zero();
  const ImuSample* nearest = &samples.front();
  for (size_t k = 0; k < samples.size(); ++k) {
    const ImuSample& s = samples[k];
    if (std::llabs(s.t_ns - t_ns) < std::llabs(nearest->t_ns - t_ns)) nearest = &s;
    if (std::llabs(s.t_ns - t_ns) > span_ns) continue;
    // The sample's mean stands for its interval's middle (the first: the next one's length).
    const int64_t length_ns =
        k > 0 ? s.t_ns - samples[k - 1].t_ns : (samples.size() > 1 ? samples[1].t_ns - s.t_ns : 0);
    const double t =
        (static_cast<double>(s.t_ns - t_ns) - 0.5 * static_cast<double>(length_ns)) * 1e-9;
    n += 1.0;
    sum_t += t;
    sum_tt += t * t;
    sum_w += s.gyro_radps;
    sum_a += s.acc_mps2;
    sum_tw += t * s.gyro_radps;
    sum_ta += t * s.acc_mps2;
  }
  const double t_mean = n > 0.0 ? sum_t / n : 0.0;
  const double s_tt = sum_tt - n * t_mean * t_mean;
  if (n < 3.0 || s_tt <= 1e-12) {
    out.gyro_radps = nearest->gyro_radps;
    out.acc_mps2 = nearest->acc_mps2;
    return out;
  }
  const auto at_zero = [&](const Eigen::Vector3d& sum_x, const Eigen::Vector3d& sum_tx) {
    const Eigen::Vector3d mean = sum_x / n;
    const Eigen::Vector3d slope = (sum_tx - t_mean * sum_x) / s_tt;
    return Eigen::Vector3d(mean - slope * t_mean);
  };
  out.gyro_radps = at_zero(sum_w, sum_tw);
  out.acc_mps2 = at_zero(sum_a, sum_ta);
  return out;
}

PreintegratedImu WithTimeOffsetUncertainty(PreintegratedImu pim, const Vec9& J, double sigma_s) {
  if (sigma_s <= 0.0) return pim;
  const Eigen::Vector3d J_rotation = J.segment<3>(kRowR);
  pim.covariance.block<3, 3>(kRowR, kRowR) +=
      (sigma_s * sigma_s) * J_rotation * J_rotation.transpose();
  return pim;
}

}  // namespace swlio::estimator

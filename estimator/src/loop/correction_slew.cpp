#include "swlio/estimator/loop/correction_slew.h"

#include <algorithm>

#include "swlio/core/lie.h"

namespace swlio::estimator {

CorrectionSlew::CorrectionSlew(const CorrectionSlewConfig& config) : config_(config) {}

void CorrectionSlew::SetTarget(const Eigen::Isometry3d& T_map_odom) {
  target_ = T_map_odom;
  settled_ = current_.isApprox(target_, 1e-12);
}

void CorrectionSlew::JumpTo(const Eigen::Isometry3d& T_map_odom) {
  current_ = target_ = T_map_odom;
  settled_ = true;
}

const Eigen::Isometry3d& CorrectionSlew::Step(int64_t t_ns, const Eigen::Isometry3d& T_odom_imu) {
  const double dt_s =
      have_time_ && t_ns > last_t_ns_ ? static_cast<double>(t_ns - last_t_ns_) * 1e-9 : 0.0;
  if (!have_time_ || t_ns > last_t_ns_) last_t_ns_ = t_ns;
  have_time_ = true;
  if (settled_) return current_;
  const Eigen::Isometry3d A = current_ * T_odom_imu;
  const lie::Vec6 d = lie::LogSE3(A.inverse() * (target_ * T_odom_imu));
  const double dp = d.head<3>().norm();
  const double dphi = d.tail<3>().norm();
  double f = 1.0;
  if (dp > 0.0) f = std::min(f, config_.max_rate_mps * dt_s / dp);
  if (dphi > 0.0) f = std::min(f, config_.max_rate_radps * dt_s / dphi);
  if (f >= 1.0) {
    current_ = target_;
    settled_ = true;
  } else {
    current_ = A * lie::ExpSE3(f * d) * T_odom_imu.inverse();
  }
  return current_;
}

}  // namespace swlio::estimator

#include "swlio/estimator/init/static_initializer.h"

#include <algorithm>
#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_moments.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

/// |mean of the second half − mean of the first half| of get(sample).
template <typename Get>
double HalfWindowDrift(const std::deque<ImuSample>& window, Get get) {
  const size_t half = window.size() / 2;
  Vec3 first = Vec3::Zero(), second = Vec3::Zero();
  for (size_t k = 0; k < half; ++k) first += get(window[k]);
  for (size_t k = half; k < window.size(); ++k) second += get(window[k]);
  first /= static_cast<double>(std::max<size_t>(half, 1));
  second /= static_cast<double>(window.size() - half);
  return (second - first).norm();
}

}  // namespace

std::string_view InitStatusReason(InitStatus status) {
  switch (status) {
    case InitStatus::kCollecting:
      return "not yet initialized: waiting for enough standing-still IMU data";
    case InitStatus::kMoving:
      return "not yet initialized: the IMU is moving or vibrating (stillness test failed)";
    case InitStatus::kBadTime:
      return "not yet initialized: IMU time went backwards, buffer restarted";
    case InitStatus::kInitialized:
      return "initialized from a standing start";
  }
  return "unknown";
}

StaticInitializer::StaticInitializer(const EstimatorConfig& config)
    : StaticInitializer(config, Options{}) {}

StaticInitializer::StaticInitializer(const EstimatorConfig& config, const Options& options)
    : gravity_mps2_(config.gravity_mps2),
      duration_ns_(SecToNs(config.init_static_duration_s)),
      options_(options) {}

void StaticInitializer::Reset() {
  window_.clear();
  result_ = StaticInitResult{};
}

const StaticInitResult& StaticInitializer::Add(const ImuSample& sample) {
  if (initialized()) return result_;
  if (!window_.empty() && sample.t_ns < window_.back().t_ns) {
    window_.clear();
    window_.push_back(sample);
    result_.status = InitStatus::kBadTime;
    return result_;
  }
  window_.push_back(sample);
  // Keep the shortest suffix that still spans the required duration.
  while (window_.size() >= 2 && window_.back().t_ns - window_[1].t_ns >= duration_ns_) {
    window_.pop_front();
  }
  result_.window_s = NsToSec(window_.back().t_ns - window_.front().t_ns);
  if (window_.back().t_ns - window_.front().t_ns < duration_ns_ || window_.size() < 2) {
    result_.status = InitStatus::kCollecting;
    return result_;
  }
  Evaluate();
  return result_;
}

void StaticInitializer::Evaluate() {
  const auto get_acc = [](const ImuSample& s) { return s.acc_mps2; };
  const auto get_gyro = [](const ImuSample& s) { return s.gyro_radps; };
  const ImuMoments acc = ComputeImuMoments(window_, get_acc);
  const ImuMoments gyro = ComputeImuMoments(window_, get_gyro);
  const double f_norm = acc.mean.norm();
  result_.acc_std_mps2 = acc.std.maxCoeff();
  result_.gyro_std_radps = gyro.std.maxCoeff();
  result_.gravity_error_mps2 = f_norm - gravity_mps2_;
  result_.gyro_mean_radps = gyro.mean.norm();
  result_.acc_drift_mps2 = HalfWindowDrift(window_, get_acc);
  result_.gyro_drift_radps = HalfWindowDrift(window_, get_gyro);
  const bool still = result_.acc_std_mps2 <= options_.max_acc_std_mps2 &&
                     result_.gyro_std_radps <= options_.max_gyro_std_radps &&
                     std::abs(result_.gravity_error_mps2) <= options_.max_gravity_error_mps2 &&
                     result_.gyro_mean_radps <= options_.max_gyro_mean_radps &&
                     result_.acc_drift_mps2 <= options_.max_acc_drift_mps2 &&
                     result_.gyro_drift_radps <= options_.max_gyro_drift_radps;
  if (!still || f_norm <= 0.0) {
    result_.status = InitStatus::kMoving;
    return;
  }
  // Up in the IMU frame is u = f/|f| = R_world_imuᵀ e_z. With R = Rz(0)·Ry(pitch)·Rx(roll),
  // Rᵀ e_z = (−sin p, sin r cos p, cos r cos p), so roll = atan2(u_y, u_z) and
  // pitch = atan2(−u_x, √(u_y² + u_z²)).
  const Vec3 up = acc.mean / f_norm;
  const double roll = std::atan2(up.y(), up.z());
  const double pitch = std::atan2(-up.x(), std::hypot(up.y(), up.z()));
  State& s = result_.state;
  s = State{};
  s.t_ns = window_.back().t_ns;
  s.T_world_imu.linear() = lie::QuatFromRpy(roll, pitch, 0.0).toRotationMatrix();
  s.bias_gyro = gyro.mean;
  s.bias_acc = result_.gravity_error_mps2 * up;  // the gravity-axis component only
  result_.gravity_imu = up;
  result_.bias_gyro_std = gyro.std / std::sqrt(static_cast<double>(window_.size()));
  result_.status = InitStatus::kInitialized;
}

}  // namespace swlio::estimator

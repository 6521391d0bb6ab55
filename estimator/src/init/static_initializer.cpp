#include "swlio/estimator/init/static_initializer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_stillness.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

// The standard error of the window's Hann mean of the rate, from the spread of its 0.2 s Hann
// means: both are means of white noise under the same kernel shape, so their variances go as
// 1/T. Pooled over the axes (one gyro noise density, as the datasheet gives): 1 s holds about
// five independent 0.2 s means per axis, and one axis alone gave 0.6–1.3× density/√T on `short`
// seeds 1–3. The tones of a vibrating chassis (15–80 Hz) leak < 1e-3 of their amplitude into the
// window's mean and < 1 % into a 0.2 s mean (imu_stillness.h), so they widen neither. The raw std
// over √N did: with the motors idling (`aggressive` world 1 seed 2008, 0.79 m/s² RMS at rest) b_g's
// prior was 3× wider than without vibration (5.2e-4 against 1.7e-4 rad/s), the window's yaw
// followed its own map's drift, and the APE rose 2.4× (bench/README.md, "Vibration and the gyro
// bias's prior").
Vec3 HannMeanStandardError(const ImuStillness& m, double window_s) {
  const double pooled_radps = std::sqrt(m.gyro_lowpass_std_axes_radps.squaredNorm() / 3.0);
  const double scale =
      window_s > kStillLowpassWindowS ? std::sqrt(kStillLowpassWindowS / window_s) : 1.0;
  return Vec3::Constant(pooled_radps * scale);
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
      // Plus the low-pass kernel (imu_stillness.h): its Hann taper barely sees the window's
      // first 0.1 s, so the still time must begin that much earlier for motion there to count.
      duration_ns_(SecToNs(config.init_static_duration_s + kStillLowpassWindowS)),
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
  const std::vector<ImuSample> samples(window_.begin(), window_.end());
  const ImuStillness m = ComputeImuStillness(samples);
  const double f_norm = m.acc_mean_mps2.norm();
  result_.acc_std_mps2 = m.acc_lowpass_std_mps2;
  result_.gyro_std_radps = m.gyro_lowpass_std_radps;
  result_.gravity_error_mps2 = f_norm - gravity_mps2_;
  result_.gyro_mean_radps = m.gyro_mean_radps.norm();
  result_.acc_drift_mps2 = (m.acc_second_half_mps2 - m.acc_first_half_mps2).norm();
  result_.gyro_drift_radps = (m.gyro_second_half_radps - m.gyro_first_half_radps).norm();
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
  const Vec3 up = m.acc_mean_mps2 / f_norm;
  const double roll = std::atan2(up.y(), up.z());
  const double pitch = std::atan2(-up.x(), std::hypot(up.y(), up.z()));
  State& s = result_.state;
  s = State{};
  s.t_ns = window_.back().t_ns;
  s.T_world_imu.linear() = lie::QuatFromRpy(roll, pitch, 0.0).toRotationMatrix();
  s.bias_gyro = m.gyro_mean_radps;
  s.bias_acc = result_.gravity_error_mps2 * up;  // the gravity-axis component only
  result_.gravity_imu = up;
  result_.bias_gyro_std = HannMeanStandardError(m, result_.window_s);
  result_.status = InitStatus::kInitialized;
}

}  // namespace swlio::estimator

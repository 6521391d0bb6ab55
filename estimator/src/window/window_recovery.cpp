// WindowEstimator's recovery: the divergence checks after every sweep, and the
// re-initialization that follows a failed one (divergence_monitor.h).

#include <algorithm>
#include <cmath>

#include "swlio/core/time.h"
#include "swlio/estimator/window/window_estimator.h"
#include "window_frame.h"

namespace swlio::estimator {
namespace {

double YawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

/// How far back the anchor of a re-initialization lies: a corrupted IMU moves the velocity by
/// metres per second within one sweep, before any bound trips (measured: 25 m/s² tripped the
/// speed bound two sweeps in, and anchoring at the sweep before added 2.3 m).
constexpr int64_t kGoodHistoryNs = 1'000'000'000;

}  // namespace

DivergenceReason WindowEstimator::CheckDivergence(const WindowResult& out) {
  SweepCheck check;
  check.state = StateOf(*frames_.back());
  check.match_failed = out.odometry.status == OdometryStatus::kMatchFailed;
  check.prediction_error_m = out.prediction_error_m;
  check.prediction_error_rad = out.prediction_error_rad;
  const DivergenceReason reason = divergence_.Check(check);
  if (reason != DivergenceReason::kNone) {
    Reinitialize();
    return reason;
  }
  if (out.odometry.status == OdometryStatus::kTracking) {
    good_.push_back(check.state);
    while (good_.size() > 1 && good_[1].t_ns <= check.state.t_ns - kGoodHistoryNs)
      good_.pop_front();
  }
  return reason;
}

void WindowEstimator::Reinitialize() {
  ++reinitializations_;
  divergence_.Reset();
  frames_.clear();
  prior_ = MarginalizationResult{};
  plane_map_ = VoxelMap(config_.odometry.plane_map);
  edge_map_ = VoxelMap(config_.odometry.edge_map);
  have_keyframe_ = false;
  std::fill(gravity_tilt_.begin(), gravity_tilt_.end(), 0.0);
  init_sigma_velocity_mps_ = config_.init_sigma_velocity_mps;
  init_sigma_tilt_rad_ = config_.init_sigma_rotation_rad;
  init_sigma_bias_acc_mps2_ = config_.init_sigma_bias_acc_mps2;
  init_sigma_bias_gyro_radps_.setConstant(config_.init_sigma_bias_gyro_radps);
  initializer_.Reset();
  bootstrap_.Reset();
  initialized_ = false;
  if (!good_.empty()) anchor_ = good_.front();
  good_.clear();
  // As before the first initialization: the last second of IMU, for the first IMU factor.
  if (!imu_.empty()) {
    const int64_t t_newest = imu_.back().t_ns;
    while (!imu_.empty() && imu_.front().t_ns < t_newest - kNsPerSec) imu_.pop_front();
  }
}

void WindowEstimator::Reset() {
  // Not a divergence: the newest good state is believable (Reinitialize takes the oldest of
  // the last second, as a divergence may have begun before a check tripped).
  const std::optional<State> newest =
      good_.empty() ? std::nullopt : std::optional<State>(good_.back());
  Reinitialize();
  if (newest) anchor_ = newest;
}

Eigen::Isometry3d WindowEstimator::AnchorFor(const Eigen::Isometry3d& T_new_imu,
                                             int64_t t_ns,
                                             bool extrapolate) const {
  if (!anchor_) return Eigen::Isometry3d::Identity();
  const State& good = *anchor_;
  Eigen::Vector3d p_world = good.T_world_imu.translation();
  if (extrapolate && t_ns > good.t_ns) {
    // Constant velocity, at most kMaxExtrapolationS: beyond that the guess is no better.
    constexpr double kMaxExtrapolationS = 5.0;
    const double dt_s = std::min(kMaxExtrapolationS, static_cast<double>(t_ns - good.t_ns) * 1e-9);
    p_world += good.vel_world * dt_s;
  }
  // Both frames are gravity-aligned: only yaw and translation differ.
  const double dyaw = YawOf(good.T_world_imu.linear()) - YawOf(T_new_imu.linear());
  Eigen::Isometry3d T_fix = Eigen::Isometry3d::Identity();
  T_fix.linear() = Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_fix.translation() = p_world - T_fix.linear() * T_new_imu.translation();
  return T_fix;
}

}  // namespace swlio::estimator

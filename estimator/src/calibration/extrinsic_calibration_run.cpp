#include "swlio/estimator/calibration/extrinsic_calibration_run.h"

#include <vector>

namespace swlio::estimator {

ExtrinsicCalibrationRun::ExtrinsicCalibrationRun(const LidarOdometryConfig& odometry,
                                                 double seconds,
                                                 double retry_s)
    : config_(odometry),
      odometry_(odometry),
      window_ns_(static_cast<int64_t>(seconds * 1e9)),
      retry_ns_(static_cast<int64_t>(retry_s * 1e9)) {}

void ExtrinsicCalibrationRun::AddImu(const ImuSample& sample) {
  imu_.push_back(sample);
  odometry_.AddImu(sample);
}

void ExtrinsicCalibrationRun::AddScan(const Scan& scan) {
  const OdometryResult r = odometry_.AddScan(scan);
  if (r.status != OdometryStatus::kTracking) return;
  // The pose the odometry settled on, in its LiDAR frame (independent of the guess it used).
  poses_.push_back({r.state.t_ns, r.state.T_world_imu * config_.T_imu_lidar, r.match.hessian});
  if (next_try_ns_ == 0) next_try_ns_ = poses_.front().t_ns + window_ns_;
  DropOld();
}

void ExtrinsicCalibrationRun::DropOld() {
  // Up to twice the stretch: a retry adds the new turns to what came before.
  while (!poses_.empty() && poses_.front().t_ns < poses_.back().t_ns - 2 * window_ns_) {
    poses_.pop_front();
  }
  // Samples from one before the first pose on (pre-integration interpolates at the pose).
  while (imu_.size() > 1 && !poses_.empty() && imu_[1].t_ns <= poses_.front().t_ns) {
    imu_.pop_front();
  }
}

std::optional<ExtrinsicCalibration> ExtrinsicCalibrationRun::TryCalibrate() {
  if (poses_.empty() || next_try_ns_ == 0 || poses_.back().t_ns < next_try_ns_) return {};
  next_try_ns_ = poses_.back().t_ns + retry_ns_;
  ++attempts_;
  // Poses the samples span (the newest sweep may end after the newest sample).
  std::vector<StampedLidarPose> poses(poses_.begin(), poses_.end());
  while (!poses.empty() && !imu_.empty() && poses.back().t_ns > imu_.back().t_ns) poses.pop_back();
  const std::vector<ImuSample> imu(imu_.begin(), imu_.end());
  ExtrinsicCalibration c = CalibrateExtrinsic(config_.estimator, poses, imu, config_.T_imu_lidar);
  last_message_ = c.message;
  if (!c.ok) return {};
  return c;
}

}  // namespace swlio::estimator

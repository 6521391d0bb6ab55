// WindowEstimator's standstill detection: a frame whose IMU interval shows rest, and whose
// sweep registered where the window already was, gets a zero-velocity factor (standstill.h).

#include <algorithm>
#include <optional>
#include <vector>

#include "swlio/core/time.h"

#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"
#include "swlio/estimator/window/window_estimator.h"
#include "window_frame.h"

namespace swlio::estimator {

bool WindowEstimator::AttachStandstill(Frame* frame, const Eigen::Vector3d& p_registered) {
  const StandstillConfig& c = config_.standstill;
  if (!c.enabled || frames_.empty()) return false;
  const Frame& previous = *frames_.back();
  // The frame's interval, or the last imu_window_s when that is longer (vibration).
  const int64_t from_ns = std::min(previous.t_ns, frame->t_ns - SecToNs(c.imu_window_s));
  std::vector<ImuSample> interval;
  for (const ImuSample& s : recent_imu_) {
    if (s.t_ns > from_ns && s.t_ns <= frame->t_ns) interval.push_back(s);
  }
  // The IMU attitude against gravity: the map frame rotated by its estimated tilt.
  const Eigen::Matrix3d R_gravity_imu =
      GravityTiltRotation(gravity_tilt_.data()) * PoseFromParameters(frame->pose.data()).linear();
  const std::optional<double> sigma_mps =
      ImuAtRest(interval, R_gravity_imu, previous.BiasAcc(), previous.BiasGyro(),
                config_.odometry.estimator.gravity_mps2, c);
  if (!sigma_mps) return false;
  // The LiDAR must agree: an IMU cannot tell a constant-velocity drive from rest.
  const Frame& oldest = *frames_.front();
  const double dt_s = static_cast<double>(frame->t_ns - oldest.t_ns) * 1e-9;
  const Eigen::Vector3d p_oldest = PoseFromParameters(oldest.pose.data()).translation();
  if ((p_registered - p_oldest).norm() > c.max_lidar_speed_mps * dt_s) return false;
  frame->zero_velocity = std::make_unique<ZeroVelocityFactor>(*sigma_mps);
  ++standstill_frames_;
  return true;
}

}  // namespace swlio::estimator

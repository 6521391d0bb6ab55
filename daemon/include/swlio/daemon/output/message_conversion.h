#pragma once
/// @file
/// Estimator values → the ROS 2-shaped messages of ipc/messages.h.
///
/// Frames: the pose is T_world_imu (the IMU body in the map frame `world_frame`); the twist of
/// nav_msgs/Odometry is in the body frame (`body_frame`), as ROS specifies (REP 105 / the
/// Odometry message comment). Covariance order is ROS's (x, y, z, rotation about X, Y, Z) with
/// the rotation error taken about the world axes (δθ with R = Exp(δθ)·R̂, as state_covariance.h
/// defines it).

#include <string>

#include "swlio/core/types.h"
#include "swlio/estimator/window/state_covariance.h"
#include "swlio/ipc/messages.h"

namespace swlio::daemon {

struct FrameIds {
  std::string world = "map";
  std::string body = "imu_link";
};

ipc::Pose ToPose(const State& state);

/// The 6×6 pose block of a 15×15 state covariance in ROS order; zeros when not valid.
ipc::Covariance6 PoseCovariance(const estimator::StateCovariance& covariance);

ipc::PoseWithCovarianceStamped ToPoseMessage(const State& state,
                                             const estimator::StateCovariance& covariance,
                                             const FrameIds& frames);

/// `gyro_imu_radps`: the bias-corrected angular rate in the body frame.
ipc::Odometry ToOdometryMessage(const State& state,
                                const Eigen::Vector3d& gyro_imu_radps,
                                const estimator::StateCovariance& covariance,
                                const FrameIds& frames);

}  // namespace swlio::daemon

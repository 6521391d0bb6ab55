#pragma once
/// @file
/// Estimator values → the ROS 2-shaped messages of ipc/messages.h, for the robot base.
///
/// Frames (REP 105): the estimator's state is the IMU's, T_world_imu; the published pose is the
/// base's, T_world_base = T_world_imu · T_imu_base (the base frame from the wheel configuration,
/// `estimator.window.wheel.T_imu_base`; identity when not configured). `world` is `map` for the
/// corrected poses and `odom` for the estimator's own. The twist of nav_msgs/Odometry is in the
/// child frame, base_link, as the Odometry message specifies. Covariance order is ROS's (x, y,
/// z, rotation about X, Y, Z) with the rotation error taken about the world axes (δθ with
/// R = Exp(δθ)·R̂, as state_covariance.h defines it).

#include <Eigen/Geometry>
#include <string>

#include "swlio/core/types.h"
#include "swlio/estimator/window/state_covariance.h"
#include "swlio/ipc/ipc_config.h"
#include "swlio/ipc/messages.h"

namespace swlio::daemon {

/// The published frames' names and where the base and the sensors sit on the robot.
struct OutputFrames {
  ipc::FrameNames names;
  Eigen::Isometry3d T_imu_base = Eigen::Isometry3d::Identity();   ///< base_link in the IMU frame
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();  ///< LiDAR in the IMU frame
};

/// The base's motion from the IMU's state.
///
///   T_world_base = T_world_imu · T_imu_base
///   ω_base       = R_imu_baseᵀ · ω_imu
///   v_base       = R_world_baseᵀ · (v_world_imu + R_world_imu (ω_imu × p_imu_base))
///
/// v_base is the velocity of the base's origin (a point rigidly attached at p_imu_base in the
/// IMU frame), in base axes: the IMU's velocity plus the rotation's lever-arm term.
struct BaseMotion {
  Eigen::Isometry3d T_world_base = Eigen::Isometry3d::Identity();
  Eigen::Vector3d vel_base_mps = Eigen::Vector3d::Zero();     ///< base origin, base axes
  Eigen::Vector3d gyro_base_radps = Eigen::Vector3d::Zero();  ///< angular rate, base axes
};

/// `gyro_imu_radps`: the bias-corrected angular rate in the IMU frame.
BaseMotion ToBase(const State& state,
                  const Eigen::Vector3d& gyro_imu_radps,
                  const Eigen::Isometry3d& T_imu_base);

/// T_world_imu · T_imu_base, exactly T_world_imu when T_imu_base is the identity.
Eigen::Isometry3d BasePose(const Eigen::Isometry3d& T_world_imu,
                           const Eigen::Isometry3d& T_imu_base);

ipc::Pose ToPose(const Eigen::Isometry3d& T_world_body);
ipc::Pose ToPose(const State& state);  ///< the IMU's pose, T_world_imu

/// The 6×6 pose block of a 15×15 state covariance in ROS order; zeros when not valid.
ipc::Covariance6 PoseCovariance(const estimator::StateCovariance& covariance);

/// The IMU's pose covariance (ROS order, world axes) moved to a point rigidly attached at
/// `p_imu_base`: p_base = p_imu + R p_imu_base, so with R = Exp(δθ)R̂ the base's position error
/// is δp − [R̂ p_imu_base]× δθ and its rotation error is the IMU's: Σ_base = J Σ Jᵀ with
/// J = [I, −[R̂ p_imu_base]×; 0, I]. Zeros stay zeros (unknown).
ipc::Covariance6 BasePoseCovariance(const ipc::Covariance6& imu_covariance,
                                    const Eigen::Matrix3d& R_world_imu,
                                    const Eigen::Vector3d& p_imu_base);

/// nav_msgs/Odometry of base_link in `frame_id` (the IMU state's world frame: map or odom).
/// `gyro_imu_radps`: the bias-corrected angular rate in the IMU frame.
ipc::Odometry ToOdometryMessage(const State& state,
                                const Eigen::Vector3d& gyro_imu_radps,
                                const estimator::StateCovariance& covariance,
                                const Eigen::Isometry3d& T_imu_base,
                                const std::string& frame_id,
                                const std::string& child_frame_id);

/// geometry_msgs/TransformStamped: T_parent_child, the child frame's pose in the parent frame.
ipc::TransformStamped ToTransform(int64_t t_ns,
                                  const std::string& parent,
                                  const std::string& child,
                                  const Eigen::Isometry3d& T_parent_child);

/// The /tf_static sample: base_link → imu (T_imu_base⁻¹) and base_link → lidar
/// (T_imu_base⁻¹ · T_imu_lidar).
ipc::TFMessage StaticTransforms(int64_t t_ns, const OutputFrames& frames);

}  // namespace swlio::daemon

#include "swlio/daemon/output/message_conversion.h"

namespace swlio::daemon {
namespace {

/// Index of (row, col) in a row-major 6×6 ROS covariance.
size_t Row6(Eigen::Index row, Eigen::Index col) { return static_cast<size_t>(6 * row + col); }

}  // namespace

ipc::Pose ToPose(const State& state) {
  ipc::Pose p;
  const Eigen::Vector3d t = state.T_world_imu.translation();
  Eigen::Quaterniond q(state.T_world_imu.linear());
  q.normalize();
  p.position_m = {t.x(), t.y(), t.z()};
  p.orientation_xyzw = {q.x(), q.y(), q.z(), q.w()};
  return p;
}

ipc::Covariance6 PoseCovariance(const estimator::StateCovariance& covariance) {
  ipc::Covariance6 c{};
  if (!covariance.valid) return c;
  for (Eigen::Index i = 0; i < 6; ++i) {
    for (Eigen::Index j = 0; j < 6; ++j) c[Row6(i, j)] = covariance.P(i, j);
  }
  return c;
}

ipc::PoseWithCovarianceStamped ToPoseMessage(const State& state,
                                             const estimator::StateCovariance& covariance,
                                             const FrameIds& frames) {
  ipc::PoseWithCovarianceStamped m;
  m.t_ns = state.t_ns;
  m.frame_id = frames.world;
  m.pose = ToPose(state);
  m.covariance = PoseCovariance(covariance);
  return m;
}

ipc::Odometry ToOdometryMessage(const State& state,
                                const Eigen::Vector3d& gyro_imu_radps,
                                const estimator::StateCovariance& covariance,
                                const FrameIds& frames) {
  ipc::Odometry m;
  m.t_ns = state.t_ns;
  m.frame_id = frames.world;
  m.child_frame_id = frames.body;
  m.pose = ToPose(state);
  m.pose_covariance = PoseCovariance(covariance);
  const Eigen::Matrix3d R_imu_world = state.T_world_imu.linear().transpose();
  const Eigen::Vector3d v_imu = R_imu_world * state.vel_world;
  m.twist.linear_mps = {v_imu.x(), v_imu.y(), v_imu.z()};
  m.twist.angular_radps = {gyro_imu_radps.x(), gyro_imu_radps.y(), gyro_imu_radps.z()};
  if (covariance.valid) {  // body velocity: Rᵀ P_vv R (the attitude's share is neglected)
    const Eigen::Matrix3d P_v =
        R_imu_world * covariance.P.block<3, 3>(6, 6) * R_imu_world.transpose();
    for (Eigen::Index i = 0; i < 3; ++i) {
      for (Eigen::Index j = 0; j < 3; ++j) m.twist_covariance[Row6(i, j)] = P_v(i, j);
    }
  }
  return m;
}

}  // namespace swlio::daemon

#include "swlio/daemon/output/message_conversion.h"

#include "swlio/core/lie.h"

namespace swlio::daemon {
namespace {

/// Index of (row, col) in a row-major 6×6 ROS covariance.
size_t Row6(Eigen::Index row, Eigen::Index col) { return static_cast<size_t>(6 * row + col); }

bool IsIdentity(const Eigen::Isometry3d& T) { return T.matrix() == Eigen::Matrix4d::Identity(); }

}  // namespace

Eigen::Isometry3d BasePose(const Eigen::Isometry3d& T_world_imu,
                           const Eigen::Isometry3d& T_imu_base) {
  if (IsIdentity(T_imu_base)) return T_world_imu;  // bit for bit the estimator's pose
  return T_world_imu * T_imu_base;
}

BaseMotion ToBase(const State& state,
                  const Eigen::Vector3d& gyro_imu_radps,
                  const Eigen::Isometry3d& T_imu_base) {
  BaseMotion b;
  b.T_world_base = BasePose(state.T_world_imu, T_imu_base);
  const Eigen::Matrix3d R_base_imu = T_imu_base.linear().transpose();
  const Eigen::Matrix3d R_imu_world = state.T_world_imu.linear().transpose();
  // v_imu in IMU axes plus ω × lever arm (both in IMU axes), then into base axes.
  const Eigen::Vector3d v_imu = R_imu_world * state.vel_world;
  b.vel_base_mps = R_base_imu * (v_imu + gyro_imu_radps.cross(T_imu_base.translation()));
  b.gyro_base_radps = R_base_imu * gyro_imu_radps;
  return b;
}

ipc::Pose ToPose(const Eigen::Isometry3d& T_world_body) {
  ipc::Pose p;
  const Eigen::Vector3d t = T_world_body.translation();
  Eigen::Quaterniond q(T_world_body.linear());
  q.normalize();
  p.position_m = {t.x(), t.y(), t.z()};
  p.orientation_xyzw = {q.x(), q.y(), q.z(), q.w()};
  return p;
}

ipc::Pose ToPose(const State& state) { return ToPose(state.T_world_imu); }

ipc::Covariance6 PoseCovariance(const estimator::StateCovariance& covariance) {
  ipc::Covariance6 c{};
  if (!covariance.valid) return c;
  for (Eigen::Index i = 0; i < 6; ++i) {
    for (Eigen::Index j = 0; j < 6; ++j) c[Row6(i, j)] = covariance.P(i, j);
  }
  return c;
}

ipc::Covariance6 BasePoseCovariance(const ipc::Covariance6& imu_covariance,
                                    const Eigen::Matrix3d& R_world_imu,
                                    const Eigen::Vector3d& p_imu_base) {
  if (p_imu_base.isZero(0.0)) return imu_covariance;  // same point: same covariance
  Eigen::Matrix<double, 6, 6> P;
  for (Eigen::Index i = 0; i < 6; ++i) {
    for (Eigen::Index j = 0; j < 6; ++j) P(i, j) = imu_covariance[Row6(i, j)];
  }
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Identity();
  J.block<3, 3>(0, 3) = -lie::Hat(R_world_imu * p_imu_base);
  const Eigen::Matrix<double, 6, 6> P_base = J * P * J.transpose();
  ipc::Covariance6 out{};
  for (Eigen::Index i = 0; i < 6; ++i) {
    for (Eigen::Index j = 0; j < 6; ++j) out[Row6(i, j)] = P_base(i, j);
  }
  return out;
}

ipc::Odometry ToOdometryMessage(const State& state,
                                const Eigen::Vector3d& gyro_imu_radps,
                                const estimator::StateCovariance& covariance,
                                const Eigen::Isometry3d& T_imu_base,
                                const std::string& frame_id,
                                const std::string& child_frame_id) {
  const BaseMotion base = ToBase(state, gyro_imu_radps, T_imu_base);
  ipc::Odometry m;
  m.t_ns = state.t_ns;
  m.frame_id = frame_id;
  m.child_frame_id = child_frame_id;
  m.pose = ToPose(base.T_world_base);
  m.pose_covariance = BasePoseCovariance(PoseCovariance(covariance), state.T_world_imu.linear(),
                                         T_imu_base.translation());
  m.twist.linear_mps = {base.vel_base_mps.x(), base.vel_base_mps.y(), base.vel_base_mps.z()};
  m.twist.angular_radps = {base.gyro_base_radps.x(), base.gyro_base_radps.y(),
                           base.gyro_base_radps.z()};
  if (covariance.valid) {  // base velocity: R P_vv Rᵀ (the attitude's and the rate's share
                           // are neglected)
    const Eigen::Matrix3d R_base_world = base.T_world_base.linear().transpose();
    const Eigen::Matrix3d P_v =
        R_base_world * covariance.P.block<3, 3>(6, 6) * R_base_world.transpose();
    for (Eigen::Index i = 0; i < 3; ++i) {
      for (Eigen::Index j = 0; j < 3; ++j) m.twist_covariance[Row6(i, j)] = P_v(i, j);
    }
  }
  return m;
}

ipc::TransformStamped ToTransform(int64_t t_ns,
                                  const std::string& parent,
                                  const std::string& child,
                                  const Eigen::Isometry3d& T_parent_child) {
  ipc::TransformStamped t;
  t.t_ns = t_ns;
  t.frame_id = parent;
  t.child_frame_id = child;
  const ipc::Pose p = ToPose(T_parent_child);
  t.transform.translation_m = p.position_m;
  t.transform.rotation_xyzw = p.orientation_xyzw;
  return t;
}

ipc::TFMessage StaticTransforms(int64_t t_ns, const OutputFrames& frames) {
  const Eigen::Isometry3d T_base_imu = frames.T_imu_base.inverse();
  ipc::TFMessage tf;
  tf.transforms.push_back(ToTransform(t_ns, frames.names.base_link, frames.names.imu, T_base_imu));
  tf.transforms.push_back(ToTransform(t_ns, frames.names.base_link, frames.names.lidar,
                                      T_base_imu * frames.T_imu_lidar));
  return tf;
}

}  // namespace swlio::daemon

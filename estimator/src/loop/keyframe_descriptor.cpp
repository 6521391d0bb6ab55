#include "swlio/estimator/loop/keyframe_descriptor.h"

#include <vector>

namespace swlio::estimator {

Eigen::Isometry3d T_gravity_imu(const Eigen::Isometry3d& T_world_imu,
                                const Eigen::Isometry3d& T_imu_lidar) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = GravityAlignedFromBody(T_world_imu.linear());
  T.translation() = -(T.linear() * T_imu_lidar.translation());
  return T;
}

ScanContext KeyframeDescriptor(const ScanContextConfig& config, const KeyframeCloud& keyframe) {
  const Eigen::Isometry3d T_G_lidar =
      T_gravity_imu(keyframe.T_world_imu, keyframe.T_imu_lidar) * keyframe.T_imu_lidar;
  std::vector<Eigen::Vector3d> points;
  points.reserve(keyframe.planes_lidar.size() + keyframe.edges_lidar.size());
  for (const Eigen::Vector3d& p : keyframe.planes_lidar) points.push_back(T_G_lidar * p);
  for (const Eigen::Vector3d& p : keyframe.edges_lidar) points.push_back(T_G_lidar * p);
  return MakeScanContext(config, points);
}

Eigen::Isometry3d T_candidate_lidar_from_descriptor(const Eigen::Isometry3d& T_Gc_imu_c,
                                                    double yaw_rad,
                                                    const Eigen::Isometry3d& T_Gq_imu_q,
                                                    const Eigen::Isometry3d& T_imu_lidar_q) {
  Eigen::Isometry3d R_Gc_Gq = Eigen::Isometry3d::Identity();
  R_Gc_Gq.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T_Gc_imu_c.inverse() * R_Gc_Gq * T_Gq_imu_q * T_imu_lidar_q;
}

}  // namespace swlio::estimator

// WindowEstimator's restart on an online extrinsic calibration (calibrate_extrinsic_s).

#include "swlio/estimator/window/window_estimator.h"
#include "window_frame.h"

namespace swlio::estimator {
namespace {

/// `map`'s points moved by T into a new map of the same configuration.
VoxelMap Carried(const VoxelMap& map, const Eigen::Isometry3d& T, const VoxelMapConfig& config) {
  std::vector<Eigen::Vector3d> points = map.Points();
  for (Eigen::Vector3d& p : points) p = T * p;
  VoxelMap out(config);
  out.Insert(points);
  out.RemoveFar(T.translation());
  return out;
}

}  // namespace

bool WindowEstimator::ApplyCalibration(const ExtrinsicCalibration& calibration) {
  const StampedLidarPose* odometry_pose = calibration_->newest_pose();
  Frame& f = *frames_.back();
  if (odometry_pose == nullptr || odometry_pose->t_ns != f.t_ns) return false;
  PoseToParameters(calibration.T_imu_lidar, extrinsic_.data());
  ResetExtrinsicPrior();
  // The window's world and the newest IMU pose stay; the odometry's map (built at LiDAR poses,
  // so right whatever the extrinsic) is carried over so that its newest LiDAR pose lands on
  // the newest frame's with the calibrated extrinsic.
  const Eigen::Isometry3d T_world_lidar = PoseFromParameters(f.pose.data()) * T_imu_lidar();
  const Eigen::Isometry3d T_world_w0 = T_world_lidar * odometry_pose->T_w0_lidar.inverse();
  const LidarOdometry& odometry = calibration_->odometry();
  plane_map_ = Carried(odometry.plane_map(), T_world_w0, config_.odometry.plane_map);
  edge_map_ = Carried(odometry.edge_map(), T_world_w0, config_.odometry.edge_map);
  have_keyframe_ = true;
  T_world_last_keyframe_ = T_world_lidar;
  // The older frames' LiDAR rows and the prior were formed against the old map and extrinsic:
  // the window restarts from the newest frame as it stands.
  while (frames_.size() > 1) frames_.pop_front();
  f.lidar_linear.reset();
  f.ResetImu();
  f.pre.reset();
  SetRestartPrior(&f);
  return true;
}

}  // namespace swlio::estimator

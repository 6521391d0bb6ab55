#pragma once
/// @file
/// A keyframe as the odometry hands it to loop closure and map saving: its IMU pose in the
/// odometry's world frame, the extrinsic, and its de-skewed planar and edge features in its
/// own LiDAR frame (after the front end's voxel filter); and a graph node's corrected pose.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include "swlio/estimator/map/visibility_image.h"

namespace swlio::estimator {

struct KeyframeCloud {
  int64_t t_ns = 0;  ///< sweep end
  Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> planes_lidar;
  std::vector<Eigen::Vector3d> edges_lidar;
  /// The free space its whole sweep saw (visibility_image.h; at T_world_imu · T_imu_lidar in
  /// the odometry's world), for loop closure to keep moving objects out of the saved map; null
  /// when the visibility test is off. Not kept with the node.
  std::shared_ptr<const VisibilityImage> visibility;
};

/// A pose-graph node in the corrected map frame (loop_closure.h): the corrected keyframe path.
struct MapNode {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();
};

}  // namespace swlio::estimator

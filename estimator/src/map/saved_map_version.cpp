// Saved-map version 1 (before issue 32) kept each node's features and extrinsic in the RoboSense
// manual's LiDAR frame (y forward, x right, z up); version 2 keeps them in the drivers' frame
// (x forward, y left, z up; drivers/lidar_decoder.h). A manual-frame point is Rz(+90°) of the
// same point in the drivers' frame: x_manual = −y, y_manual = x.

#include "swlio/estimator/map/saved_map.h"

namespace swlio::estimator {
namespace {

void ToDriversFrame(std::vector<Eigen::Vector3d>* points) {
  for (Eigen::Vector3d& p : *points) p = Eigen::Vector3d(p.y(), -p.x(), p.z());
}

}  // namespace

void ConvertManualFrameNodes(SavedMap* map) {
  Eigen::Isometry3d T_manual_new = Eigen::Isometry3d::Identity();
  T_manual_new.linear() << 0, -1, 0, 1, 0, 0, 0, 0, 1;  // Rz(+90°)
  for (SavedMapNode& node : map->nodes) {
    ToDriversFrame(&node.planes_lidar);
    ToDriversFrame(&node.edges_lidar);
    node.T_imu_lidar = node.T_imu_lidar * T_manual_new;
  }
}

}  // namespace swlio::estimator

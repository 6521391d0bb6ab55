#pragma once
/// @file
/// A keyframe's place descriptor (scan_context.h) and the relative pose a descriptor match
/// implies, shared by loop closure and relocalization in a saved map (issue 8).
///
/// Each keyframe has a gravity-aligned frame G: origin at its LiDAR, z up (the odometry world's
/// z), x along the IMU's heading. A descriptor is made in G, so two descriptors of one place
/// differ by a yaw only; the match's yaw (p_Gc = Rz(yaw) · p_Gq) and a zero offset between the
/// two LiDARs give the guess that registration starts from.

#include <Eigen/Geometry>

#include "swlio/estimator/common/keyframe_cloud.h"
#include "swlio/estimator/loop/scan_context.h"

namespace swlio::estimator {

/// T_G_imu of a keyframe at `T_world_imu` with extrinsic `T_imu_lidar`.
Eigen::Isometry3d T_gravity_imu(const Eigen::Isometry3d& T_world_imu,
                                const Eigen::Isometry3d& T_imu_lidar);

/// The descriptor of a keyframe's planar and edge features.
ScanContext KeyframeDescriptor(const ScanContextConfig& config, const KeyframeCloud& keyframe);

/// The query's LiDAR pose in the candidate's IMU frame implied by a descriptor match:
/// T_Gc_imu_c⁻¹ · Rz(yaw_rad) · T_Gq_imu_q · T_imu_lidar_q.
Eigen::Isometry3d T_candidate_lidar_from_descriptor(const Eigen::Isometry3d& T_Gc_imu_c,
                                                    double yaw_rad,
                                                    const Eigen::Isometry3d& T_Gq_imu_q,
                                                    const Eigen::Isometry3d& T_imu_lidar_q);

}  // namespace swlio::estimator

#pragma once
/// @file
/// Verification of a loop candidate (issue 8): the newest keyframe's features registered
/// against a submap of the candidate's neighbourhood, both expressed in the candidate node's
/// IMU frame, first coarsely (wide neighbour search, for the drift) and then with the
/// odometry's settings. Accepted only when the fine registration converged, enough of the
/// planar features lie on their planes (fitness), its Hessian constrains every direction, and
/// the result stays within a plausible correction of the graph's guess.

#include <Eigen/Geometry>
#include <vector>

#include "swlio/estimator/loop/loop_closure_config.h"
#include "swlio/estimator/registration/scan_matcher.h"
#include "swlio/estimator/registration/voxel_map.h"

namespace swlio::estimator {

enum class LoopVerdict {
  kAccepted,
  kNotConverged,
  kLowFitness,
  kDegenerate,
  kImplausibleCorrection,
};

const char* ToString(LoopVerdict verdict);

struct LoopCheck {
  LoopVerdict verdict = LoopVerdict::kNotConverged;
  /// The newest keyframe's LiDAR pose in the candidate's IMU frame, as registered.
  Eigen::Isometry3d T_candidate_lidar = Eigen::Isometry3d::Identity();
  double fitness = 0.0;  ///< share of planar features within inlier_distance_m of their plane
  size_t inliers = 0;
  double min_eigenvalue = 0.0;  ///< of the fine registration's Hessian
  double correction_m = 0.0;    ///< registered against guessed pose
  double correction_rad = 0.0;
};

/// The submap around a candidate: feature maps in the candidate's IMU frame.
struct LoopSubmap {
  explicit LoopSubmap(const VoxelMapConfig& config) : planes(config), edges(config) {}
  VoxelMap planes;
  VoxelMap edges;
};

LoopCheck VerifyLoop(const LoopClosureConfig& config,
                     const std::vector<Eigen::Vector3d>& planes_lidar,
                     const std::vector<Eigen::Vector3d>& edges_lidar,
                     const LoopSubmap& submap,
                     const Eigen::Isometry3d& T_candidate_lidar_guess);

}  // namespace swlio::estimator

#pragma once
/// @file
/// Options of loop closure (loop_closure.h), apart from it so that configuration code does not
/// pull in Ceres.

#include "swlio/core/config_issue.h"
#include "swlio/estimator/gnss/gnss_config.h"
#include "swlio/estimator/loop/scan_context.h"
#include "swlio/estimator/registration/scan_matcher.h"
#include "swlio/estimator/registration/voxel_map.h"

namespace swlio::estimator {

/// Moving objects out of the saved map (visibility_image.h). Each new node's sweep (its
/// KeyframeCloud::visibility, made by the window with its own visibility settings) tests the
/// stored clouds of the nodes within check_radius_m (map frame, so a loop's correction applies),
/// and the new node's cloud is tested against the sweeps of the last `recent_nodes` nodes: a
/// person standing where the robot saw free space a moment ago goes too. A point leaves its
/// cloud after votes_to_remove seen-through tests with no confirmation in between.
struct MapVisibilityConfig {
  bool enabled = true;
  int64_t votes_to_remove = 2;
  double check_radius_m = 40.0;
  int64_t recent_nodes = 10;  ///< 29 kB each (visibility_image.h)

  ConfigIssues Validate() const;
};

struct LoopClosureConfig {
  /// Loop detection. Off, the pose graph still runs when `gnss.enabled` (GNSS edges only).
  bool enabled = true;
  /// A window keyframe becomes a graph node after this much motion since the last node.
  double keyframe_distance_m = 1.0;
  double keyframe_angle_rad = 0.2;
  /// Candidates: nodes within this distance of the newest (corrected poses) ...
  double search_radius_m = 10.0;
  /// ... and at least this much older (so the recent track is never a loop).
  double min_separation_s = 30.0;
  /// Places (issue 33: memory that stops growing on a patrol): a new node within this distance
  /// and this turn (corrected poses) of an old-enough node that keeps a cloud maps nothing new;
  /// it keeps no cloud and, after its own loop search, no descriptor (keyframe_store.h). 0 m:
  /// every node keeps both. Nodes are `keyframe_distance_m` apart, so the default finds the
  /// nearest node of an earlier pass along the same road and lane; the opposite direction is
  /// another view, kept.
  double place_radius_m = 2.0;
  double place_angle_rad = 0.35;
  /// Candidates also from the place descriptor of every node (scan_context.h): among the
  /// old-enough nodes the graph puts within search_radius_m + max_drift_ratio × the distance
  /// driven between the two, the one whose descriptor is nearest (the nearest position is not
  /// always the best view of the place). It is verified like a radius candidate, from the
  /// graph's relative pose: a substation repeats its bays every few tens of metres, and a
  /// look-alike bay further along the road matches a descriptor (and a registration started
  /// from the descriptor's pose) as well as the true place. Odometry drift is far below 1 %
  /// (bench/README.md, "Accuracy": loop943's end point's distance from the start), so the reach
  /// stays short of the next bay on most loops.
  bool descriptor_candidates = true;
  ScanContextConfig descriptor;
  double max_drift_ratio = 0.01;
  /// A detection is tried at most every this many nodes (each try is one registration).
  int attempt_every_nodes = 2;
  /// The submap a candidate is verified against: its node and this many on each side.
  int submap_half_width = 5;
  /// Its voxels are twice the local map's: the k-NN search covers the 27 voxels around a
  /// point, so 1 m voxels let a feature find its surface up to ~1.5 m away (the drift).
  VoxelMapConfig submap = {.voxel_m = 1.0, .max_points_per_voxel = 20};
  /// First registration from the graph's guess: wide neighbour search and gates for the drift
  /// (its later associations too: the guess can be a metre off).
  ScanMatcherConfig coarse = {.max_neighbor_distance_m = 3.0,
                              .huber_m = 0.3,
                              .max_residual_m = 2.0,
                              .refined_max_residual_m = 2.0,
                              .max_iterations = 30,
                              .max_associations = 8};
  /// Then from the coarse result with the odometry's matcher settings.
  ScanMatcherConfig fine;
  /// Verification: planar features within this distance of their plane are inliers ...
  double inlier_distance_m = 0.1;
  /// ... and a loop needs this share of them and this many.
  double min_fitness = 0.5;
  int min_inliers = 100;
  /// ... and the smallest eigenvalue of the fine registration's Hessian (ScanMatcher units)
  /// above this: a registration free to slide along a corridor proves nothing.
  double min_hessian_eigenvalue = 20.0;
  /// A loop may move the newest node at most this far from where the graph had it.
  double max_correction_m = 3.0;
  double max_correction_rad = 0.2;
  /// Edge noise: odometry between consecutive nodes, loops.
  double odometry_sigma_m = 0.02;
  double odometry_sigma_rad = 0.002;
  double loop_sigma_m = 0.05;
  double loop_sigma_rad = 0.005;
  /// Consistency (pose_graph.h): after a solve, a loop edge whose whitened squared residual
  /// exceeds this is switched off (worst first) and the graph solved again. 22.5 is the 99.9 %
  /// point of χ² with 6 degrees of freedom.
  double max_loop_chi2 = 22.5;
  /// Cauchy scale on loop residuals (0: none, the default; see pose_graph.h).
  double loop_kernel = 0.0;
  int max_iterations = 20;
  /// The daemon's output follows a new correction at most this fast (correction_slew.h).
  double output_max_rate_mps = 0.2;
  double output_max_rate_radps = 0.05;
  /// GNSS position factors on the nodes (off by default).
  GnssConfig gnss;
  MapVisibilityConfig visibility;

  ConfigIssues Validate() const;
};

}  // namespace swlio::estimator

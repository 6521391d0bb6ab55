#include "swlio/estimator/loop/loop_closure_config.h"

namespace swlio::estimator {

ConfigIssues MapVisibilityConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange<int64_t>(issues, "votes_to_remove", votes_to_remove, 1, 100);
  CheckInRange(issues, "check_radius_m", check_radius_m, 1.0, 1000.0);
  CheckInRange<int64_t>(issues, "recent_nodes", recent_nodes, 0, 1000);
  return issues;
}

ConfigIssues LoopClosureConfig::Validate() const {
  ConfigIssues issues;
  if (visibility.enabled) AppendWithPrefix(issues, "visibility", visibility.Validate());
  CheckPositive(issues, "keyframe_distance_m", keyframe_distance_m);
  CheckPositive(issues, "keyframe_angle_rad", keyframe_angle_rad);
  CheckPositive(issues, "search_radius_m", search_radius_m);
  CheckInRange(issues, "min_separation_s", min_separation_s, 1.0, 3600.0);
  CheckInRange(issues, "place_radius_m", place_radius_m, 0.0, 50.0);
  CheckInRange(issues, "place_angle_rad", place_angle_rad, 0.0, 3.15);
  AppendWithPrefix(issues, "descriptor", descriptor.Validate());
  if (gnss.enabled) AppendWithPrefix(issues, "gnss", gnss.Validate());
  CheckInRange(issues, "max_drift_ratio", max_drift_ratio, 0.0, 1.0);
  CheckInRange(issues, "attempt_every_nodes", attempt_every_nodes, 1, 1000);
  CheckInRange(issues, "submap_half_width", submap_half_width, 0, 100);
  AppendWithPrefix(issues, "submap", submap.Validate());
  AppendWithPrefix(issues, "coarse", coarse.Validate());
  AppendWithPrefix(issues, "fine", fine.Validate());
  CheckPositive(issues, "inlier_distance_m", inlier_distance_m);
  CheckInRange(issues, "min_fitness", min_fitness, 0.0, 1.0);
  CheckInRange(issues, "min_inliers", min_inliers, 1, 1000000);
  CheckInRange(issues, "min_hessian_eigenvalue", min_hessian_eigenvalue, 0.0, 1e9);
  CheckPositive(issues, "max_correction_m", max_correction_m);
  CheckPositive(issues, "max_correction_rad", max_correction_rad);
  CheckPositive(issues, "odometry_sigma_m", odometry_sigma_m);
  CheckPositive(issues, "odometry_sigma_rad", odometry_sigma_rad);
  CheckPositive(issues, "loop_sigma_m", loop_sigma_m);
  CheckPositive(issues, "loop_sigma_rad", loop_sigma_rad);
  CheckInRange(issues, "max_loop_chi2", max_loop_chi2, 0.0, 1e6);
  CheckInRange(issues, "loop_kernel", loop_kernel, 0.0, 1e3);
  CheckInRange(issues, "max_iterations", max_iterations, 1, 1000);
  CheckPositive(issues, "output_max_rate_mps", output_max_rate_mps);
  CheckPositive(issues, "output_max_rate_radps", output_max_rate_radps);
  return issues;
}

}  // namespace swlio::estimator

#include "swlio/estimator/window/window_estimator_config.h"

#include <utility>

namespace swlio::estimator {

ConfigIssues WindowEstimatorConfig::Validate() const {
  ConfigIssues issues;
  AppendWithPrefix(issues, "odometry", odometry.Validate());
  if (dynamic_init) {
    DynamicBootstrapConfig b = bootstrap;
    b.odometry = odometry;  // as the estimator uses it (its own keys are checked above)
    for (const ConfigIssue& issue : b.Validate()) {
      if (issue.key.rfind("odometry.", 0) != 0)
        issues.push_back({"bootstrap." + issue.key, issue.reason});
    }
  }
  AppendWithPrefix(issues, "divergence", divergence.Validate());
  if (wheel.enabled) AppendWithPrefix(issues, "wheel", wheel.Validate());
  if (standstill.enabled) AppendWithPrefix(issues, "standstill", standstill.Validate());
  if (imu_noise_adapter.enabled) {
    AppendWithPrefix(issues, "imu_noise_adapter", imu_noise_adapter.Validate());
  }
  if (time_offset.enabled) AppendWithPrefix(issues, "time_offset", time_offset.Validate());
  if (visibility.enabled) AppendWithPrefix(issues, "visibility", visibility.Validate());
  CheckInRange<size_t>(issues, "window_size", window_size, 2, 50);
  CheckInRange(issues, "max_iterations", max_iterations, 1, 50);
  CheckInRange(issues, "reassociations", reassociations, 0, 5);
  // The two edge settings by the front end's own rules, as WithWindowFeatures applies them.
  for (ConfigIssue& issue : WithWindowFeatures(*this).odometry.front_end.features.Validate()) {
    if (issue.key == "edge_threshold_m2" || issue.key == "max_edges_per_sector")
      issues.push_back(std::move(issue));
  }
  // VoxelMapConfig's range; the LiDAR-only mode's key allows 10–500 m.
  CheckInRange(issues, "local_map_radius_m", local_map_radius_m, 10.0, 500.0);
  CheckPositive(issues, "lidar_sigma_m", lidar_sigma_m);
  CheckPositive(issues, "huber_m", huber_m);
  CheckPositive(issues, "static_max_speed_mps", static_max_speed_mps);
  CheckPositive(issues, "degenerate_eigenvalue", degenerate_eigenvalue);
  CheckInRange(issues, "lidar_floor_sigma_m", lidar_floor_sigma_m, 0.0, 1.0);
  CheckInRange(issues, "lidar_floor_sigma_tilt_rad", lidar_floor_sigma_tilt_rad, 0.0, 0.5);
  CheckInRange(issues, "lidar_floor_sigma_yaw_rad", lidar_floor_sigma_yaw_rad, 0.0, 0.5);
  CheckPositive(issues, "extrinsic_prior_sigma_m", extrinsic_prior_sigma_m);
  CheckPositive(issues, "extrinsic_prior_sigma_rad", extrinsic_prior_sigma_rad);
  CheckInRange(issues, "calibrate_extrinsic_s", calibrate_extrinsic_s, 0.0, 600.0);
  CheckPositive(issues, "calibrate_retry_s", calibrate_retry_s);
  CheckPositive(issues, "init_sigma_position_m", init_sigma_position_m);
  CheckPositive(issues, "init_sigma_rotation_rad", init_sigma_rotation_rad);
  CheckPositive(issues, "init_sigma_velocity_mps", init_sigma_velocity_mps);
  CheckPositive(issues, "init_sigma_bias_acc_mps2", init_sigma_bias_acc_mps2);
  CheckPositive(issues, "init_sigma_bias_gyro_radps", init_sigma_bias_gyro_radps);
  CheckInRange(issues, "bias_prior_sigma_acc_mps2", bias_prior_sigma_acc_mps2, 0.0, 10.0);
  CheckInRange(issues, "bias_prior_sigma_gyro_radps", bias_prior_sigma_gyro_radps, 0.0, 1.0);
  return issues;
}

WindowEstimatorConfig WithWindowFeatures(WindowEstimatorConfig config) {
  config.odometry.front_end.features.edge_threshold_m2 = config.edge_threshold_m2;
  config.odometry.front_end.features.max_edges_per_sector = config.max_edges_per_sector;
  config.odometry.plane_map.radius_m = config.local_map_radius_m;
  config.odometry.edge_map.radius_m = config.local_map_radius_m;
  return config;
}

}  // namespace swlio::estimator

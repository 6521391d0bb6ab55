#include "swlio/estimator/common/estimator_config.h"

#include "swlio/core/lie.h"

#include <algorithm>
#include <cmath>

namespace swlio::estimator {

ConfigIssues ImuNoiseConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "acc_noise_density_mps2_per_sqrthz", acc_noise_density_mps2_per_sqrthz, 1e-6,
               1.0);
  CheckInRange(issues, "gyro_noise_density_radps_per_sqrthz", gyro_noise_density_radps_per_sqrthz,
               1e-7, 0.1);
  CheckInRange(issues, "acc_bias_random_walk_mps3_per_sqrthz", acc_bias_random_walk_mps3_per_sqrthz,
               1e-8, 1.0);
  CheckInRange(issues, "gyro_bias_random_walk_radps2_per_sqrthz",
               gyro_bias_random_walk_radps2_per_sqrthz, 1e-9, 0.1);
  return issues;
}

ConfigIssues ExtrinsicConfig::Validate() const {
  ConfigIssues issues;
  const bool t_ok = std::all_of(translation_m.begin(), translation_m.end(),
                                [](double v) { return std::isfinite(v) && std::abs(v) <= 5.0; });
  CheckThat(issues, t_ok, "translation_m", "each component must be finite and within ±5 m");
  const bool r_ok = std::all_of(rotation_rpy_deg.begin(), rotation_rpy_deg.end(),
                                [](double v) { return std::isfinite(v) && std::abs(v) <= 180.0; });
  CheckThat(issues, r_ok, "rotation_rpy_deg", "each angle must be within ±180°");
  return issues;
}

ConfigIssues EstimatorConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues, mode == "tightly-coupled" || mode == "lidar-only", "mode",
            "must be tightly-coupled or lidar-only, got '" + mode + "'");
  AppendWithPrefix(issues, "imu_noise", imu_noise.Validate());
  AppendWithPrefix(issues, "extrinsic_imu_lidar", extrinsic_imu_lidar.Validate());
  CheckInRange(issues, "gravity_mps2", gravity_mps2, 9.7, 9.9);
  CheckInRange(issues, "output_rebase_rate_mps", output_rebase_rate_mps, 0.0, 10.0);
  CheckInRange(issues, "output_rebase_rate_radps", output_rebase_rate_radps, 0.0, 10.0);
  CheckThat(issues, (output_rebase_rate_mps > 0.0) == (output_rebase_rate_radps > 0.0),
            "output_rebase_rate_radps",
            "must be 0 exactly when output_rebase_rate_mps is (a rotation never taken in)");
  CheckInRange(issues, "init_static_duration_s", init_static_duration_s, 0.2, 30.0);
  CheckInRange(issues, "plane_voxel_m", plane_voxel_m, 0.05, 2.0);
  CheckInRange(issues, "edge_voxel_m", edge_voxel_m, 0.05, 2.0);
  CheckInRange(issues, "local_map_radius_m", local_map_radius_m, 10.0, 500.0);
  return issues;
}

Eigen::Isometry3d ExtrinsicConfig::ToIsometry() const {
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::QuatFromRpy(rotation_rpy_deg[0] * kDegToRad, rotation_rpy_deg[1] * kDegToRad,
                                rotation_rpy_deg[2] * kDegToRad)
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(translation_m[0], translation_m[1], translation_m[2]);
  return T;
}

ExtrinsicConfig ExtrinsicConfig::FromIsometry(const Eigen::Isometry3d& T) {
  constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
  const Eigen::Vector3d rpy_deg = lie::RpyFromRotation(T.linear()) * kRadToDeg;
  ExtrinsicConfig c;
  c.translation_m = {T.translation().x(), T.translation().y(), T.translation().z()};
  c.rotation_rpy_deg = {rpy_deg.x() + 0.0, rpy_deg.y() + 0.0, rpy_deg.z() + 0.0};  // no -0
  return c;
}

}  // namespace swlio::estimator

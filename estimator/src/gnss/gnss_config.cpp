#include "swlio/estimator/gnss/gnss_config.h"

#include <cmath>

namespace swlio::estimator {

ConfigIssues GnssConfig::Validate() const {
  ConfigIssues issues;
  const bool origin_unset =
      std::isnan(origin_lat_deg) && std::isnan(origin_lon_deg) && std::isnan(origin_height_m);
  if (!origin_unset) {
    CheckInRange(issues, "origin_lat_deg", origin_lat_deg, -90.0, 90.0);
    CheckInRange(issues, "origin_lon_deg", origin_lon_deg, -180.0, 180.0);
    CheckInRange(issues, "origin_height_m", origin_height_m, -1000.0, 10000.0);
  }
  CheckThat(issues, antenna_imu_m.allFinite() && antenna_imu_m.norm() < 10.0, "antenna_imu_m",
            "must be finite and within 10 m of the IMU");
  CheckInRange(issues, "min_fix_type", min_fix_type, 1, 5);
  CheckInRange(issues, "max_h_acc_m", max_h_acc_m, 0.01, 1000.0);
  CheckInRange(issues, "sigma_scale", sigma_scale, 0.01, 100.0);
  CheckInRange(issues, "min_sigma_m", min_sigma_m, 0.001, 100.0);
  CheckInRange(issues, "min_interval_s", min_interval_s, 0.0, 60.0);
  CheckInRange(issues, "correlation_time_s", correlation_time_s, 0.0, 3600.0);
  CheckInRange(issues, "max_interpolation_s", max_interpolation_s, 0.01, 30.0);
  CheckInRange(issues, "align_min_distance_m", align_min_distance_m, 1.0, 10000.0);
  CheckInRange(issues, "optimize_every_fixes", optimize_every_fixes, 1, 10000);
  CheckInRange(issues, "gate_sigmas", gate_sigmas, 1.0, 1000.0);
  CheckInRange(issues, "gate_reset_after", gate_reset_after, 1, 100000);
  CheckInRange(issues, "kernel", kernel, 0.0, 100.0);
  CheckInRange(issues, "max_chi2", max_chi2, 0.0, 1e6);
  return issues;
}

}  // namespace swlio::estimator

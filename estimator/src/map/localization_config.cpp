#include "swlio/estimator/map/localization_config.h"

namespace swlio::estimator {

ConfigIssues LocalizationConfig::Validate() const {
  ConfigIssues issues;
  AppendWithPrefix(issues, "registration", registration.Validate());
  CheckInRange(issues, "relocalize_max_descriptor_distance", relocalize_max_descriptor_distance,
               0.0, 1.0);
  CheckInRange(issues, "relocalize_candidates", relocalize_candidates, 1, 100);
  CheckPositive(issues, "relocalize_max_correction_m", relocalize_max_correction_m);
  CheckPositive(issues, "relocalize_max_correction_rad", relocalize_max_correction_rad);
  CheckInRange(issues, "confirmations", confirmations, 0, 100);
  CheckInRange(issues, "relocalize_every_m", relocalize_every_m, 0.0, 100.0);
  CheckInRange(issues, "relocalize_every_rad", relocalize_every_rad, 0.0, 3.2);
  CheckInRange(issues, "track_every_m", track_every_m, 0.0, 100.0);
  CheckInRange(issues, "track_every_rad", track_every_rad, 0.0, 3.2);
  CheckInRange(issues, "relocalize_min_margin", relocalize_min_margin, 0.0, 1.0);
  CheckPositive(issues, "distinct_m", distinct_m);
  CheckPositive(issues, "submap_radius_m", submap_radius_m);
  CheckInRange(issues, "submap_max_nodes", submap_max_nodes, 1, 10000);
  CheckInRange(issues, "track_min_fitness", track_min_fitness, 0.0, 1.0);
  CheckPositive(issues, "track_max_correction_m", track_max_correction_m);
  CheckPositive(issues, "track_max_correction_rad", track_max_correction_rad);
  CheckInRange(issues, "lost_after_failures", lost_after_failures, 1, 100000);
  return issues;
}

}  // namespace swlio::estimator

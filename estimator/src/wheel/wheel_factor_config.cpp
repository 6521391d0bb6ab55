#include "swlio/estimator/wheel/wheel_factor_config.h"

namespace swlio::estimator {

ConfigIssues WheelFactorConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "sigma_forward_mps", sigma_forward_mps, 1e-4, 10.0);
  CheckInRange(issues, "sigma_lateral_mps", sigma_lateral_mps, 1e-4, 10.0);
  CheckInRange(issues, "sigma_vertical_mps", sigma_vertical_mps, 1e-4, 10.0);
  CheckInRange(issues, "max_gap_s", max_gap_s, 1e-3, 1.0);
  CheckInRange(issues, "max_innovation_mps", max_innovation_mps, 0.01, 20.0);
  AppendWithPrefix(issues, "T_imu_base", T_imu_base.Validate());
  return issues;
}

}  // namespace swlio::estimator

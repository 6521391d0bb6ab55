#pragma once
/// @file
/// Instantaneous IMU samples (the rate and specific force at their stamps, as many IMU drivers
/// publish sensor_msgs/Imu) turned into the interval means the estimator takes (core/types.h):
/// each output is the trapezoidal mean of a sample and the one before it, stamped at the later
/// one, i.e. the midpoint rule's step values. An Xsens MTi's own samples are already means and
/// need none of this.

#include <optional>

#include "swlio/core/types.h"

namespace swlio::estimator {

class ImuIntervalMeans {
 public:
  /// The mean over the interval since the previous sample. The first sample, and one not newer
  /// than the previous (which restarts the pairing), pass as they are.
  ImuSample Next(const ImuSample& instant);

 private:
  std::optional<ImuSample> previous_;
};

}  // namespace swlio::estimator

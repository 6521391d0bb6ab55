#pragma once
// Hand-made sweeps for the front-end tests: beams of a 16-ring sensor (−15°…+15° in 2° steps)
// through the centres of a 1800-column range image.

#include <Eigen/Core>
#include <cmath>
#include <numbers>

#include "swlio/core/types.h"

namespace swlio::estimator::test {

inline constexpr double kDegToRad = std::numbers::pi / 180.0;

/// A point at the centre of image column `column` (1800 columns), ring `ring` of a 16-beam
/// sensor (−15°…+15° in 2° steps), at range `range_m`, in the drivers' frame (x forward, y
/// left; azimuth clockwise from forward, column 0 behind the sensor).
inline LidarPoint At(int ring, int column, double range_m) {
  const double azimuth = (column + 0.5) / 1800.0 * 2.0 * std::numbers::pi - std::numbers::pi;
  const double elevation = (-15.0 + 2.0 * ring) * kDegToRad;
  LidarPoint p;
  p.xyz_m =
      (range_m * Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                                 -std::cos(elevation) * std::sin(azimuth), std::sin(elevation)))
          .cast<float>();
  p.ring = static_cast<uint16_t>(ring);
  return p;
}

}  // namespace swlio::estimator::test

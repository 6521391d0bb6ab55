#pragma once
/// @file
/// Mean and per-axis sample standard deviation of one IMU quantity over a run of samples: the
/// stillness tests of the static initialization and of standstill detection.

#include <Eigen/Core>
#include <algorithm>

#include "swlio/core/types.h"

namespace swlio::estimator {

struct ImuMoments {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d std = Eigen::Vector3d::Zero();  ///< per axis, n − 1 in the denominator
};

/// Over `samples` (any range of ImuSample, not empty), of get(sample), e.g. the specific force.
template <typename Samples, typename Get>
ImuMoments ComputeImuMoments(const Samples& samples, Get get) {
  ImuMoments m;
  for (const ImuSample& s : samples) m.mean += get(s);
  const double n = static_cast<double>(samples.size());
  m.mean /= n;
  Eigen::Vector3d var = Eigen::Vector3d::Zero();
  for (const ImuSample& s : samples) var += (get(s) - m.mean).cwiseAbs2();
  m.std = (var / std::max(n - 1.0, 1.0)).cwiseSqrt();
  return m;
}

}  // namespace swlio::estimator

#pragma once
/// @file
/// Inputs for estimator contract tests: an IMU sample of a level robot (optionally
/// accelerating along x) and a sweep of 100 points along a wall, too few features for any map
/// correspondence.

#include "swlio/core/time.h"
#include "swlio/core/types.h"

namespace swlio::estimator::test {

inline ImuSample LevelImu(int64_t t_ns, double acc_x_mps2 = 0.0) {
  ImuSample s;
  s.t_ns = t_ns;
  s.acc_mps2 = Eigen::Vector3d(acc_x_mps2, 0.0, 9.80665);
  return s;
}

inline Scan WallSweep(int64_t t_start_ns) {
  Scan scan;
  scan.t_start_ns = t_start_ns;
  scan.t_end_ns = t_start_ns + 99 * kNsPerMs;
  for (int i = 0; i < 100; ++i) {
    LidarPoint p;
    p.xyz_m = Eigen::Vector3f(5.0f, 0.01f * static_cast<float>(i), -1.0f);
    p.dt_ns = i * kNsPerMs;
    scan.points.push_back(p);
  }
  return scan;
}

}  // namespace swlio::estimator::test

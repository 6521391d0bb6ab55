#pragma once
/// @file
/// Whole LiDAR sweeps straight from the simulator's ground truth, for estimator tests and
/// benchmarks: every valid return as a `swlio::LidarPoint` with its true surface class, ring
/// (0 = lowest beam, from the vertical angles) and time, moved with the true poses into the
/// LiDAR frame at the sweep's last firing (a perfect de-skew).

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/lidar_sim.h"
#include "swlio/core/types.h"

namespace swlio::sim {

struct LabelledScan {
  Scan scan;                      ///< points in the LiDAR frame at `t_end_ns`
  std::vector<SurfaceClass> cls;  ///< true class, one per point
  /// One per point: 1 when it came from an actor that moves at some time during the drive (a
  /// walking person, a driving vehicle, a parked one that leaves), else 0 (SimReturn::moving).
  std::vector<uint8_t> moving;
  std::vector<Eigen::Vector3d> p_world;  ///< true hit point, one per point
  Eigen::Isometry3d T_world_lidar_end = Eigen::Isometry3d::Identity();
};

/// Cuts the simulated returns into sweeps of one motor turn (60/rpm s), starting at host 0.
class LabelledScanSource {
 public:
  /// `setup` must outlive the source.
  explicit LabelledScanSource(const SimSetup& setup);

  /// The next sweep starting at or after `t_min_s`; false when the route ends. Skipped
  /// sweeps are not assembled, but their rays are still cast (the simulator runs in order).
  bool Next(LabelledScan* out, double t_min_s = 0.0);

 private:
  Eigen::Isometry3d LidarPose(double t_s) const;

  const SimSetup* setup_;
  LidarSimulator lidar_;
  std::vector<uint16_t> ring_of_channel_;
  std::vector<SimReturn> pending_;
  std::vector<SimReturn> packet_;
  int64_t period_ns_;
  int64_t next_start_ns_ = 0;
  bool done_ = false;
};

}  // namespace swlio::sim

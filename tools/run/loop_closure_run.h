#pragma once
/// @file
/// swlio-run's loop closure (`--loop-closure on`): every tracked sweep's pose goes through
/// LoopClosure (estimator/loop/loop_closure.h), keyframes become graph nodes, and the trajectory is
/// written twice: as it would have been published (each sweep with the correction known at
/// its time: `--out`) and after the run with the final graph (`--out-optimized`; its nodes alone:
/// `--out-path`). The loop attempts can be written as CSV (`--loops`). With GNSS (`--gnss on`) the
/// fixes go in too, and the final trajectory can be written georeferenced, in the local ENU frame
/// (`--out-enu`). Timing: thread CPU time of each AddKeyframe (and of each AddGnss that optimized).

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/estimator/common/stage_timer.h"
#include "swlio/estimator/loop/loop_closure.h"
#include "swlio/estimator/map/map_pcd.h"

namespace swlio::tools {

class LoopClosureRun {
 public:
  /// `time`: the recording's time base; the written files' stamps go back to host time.
  LoopClosureRun(const estimator::LoopClosureConfig& config,
                 estimator::NowNsFn now_ns,
                 daemon::TimeScale time = {});

  /// A tracked sweep's state (odometry frame) and its keyframe (null unless one); returns the
  /// state in the map frame with the correction known now.
  State OnSweep(const State& odom, const estimator::KeyframeCloud* keyframe);

  /// A GNSS fix (time order with the sweeps).
  void OnGnss(const GnssFix& fix);

  /// Every sweep passed to OnSweep, corrected with the final graph (TUM).
  bool WriteOptimized(const std::string& path) const;
  /// The final graph's nodes (one per keyframe) at their poses (TUM): the keyframe path the
  /// daemon publishes last.
  bool WritePath(const std::string& path) const;
  /// The same in the local ENU frame (GNSS); false with *error before the alignment.
  bool WriteEnu(const std::string& path, std::string* error) const;
  /// One row per verified candidate.
  bool WriteLoops(const std::string& path) const;
  /// `"loops": {...}` for the summary JSON: counts and the update times (ms).
  std::string SummaryJson() const;
  /// The final graph as a saved map (saved_map.h) at `path`, and its merged cloud as PCD at
  /// `pcd_path` unless empty; false with *error.
  bool SaveMap(const std::string& path, const std::string& pcd_path, std::string* error) const;

 private:
  /// Accepted loops found by the place descriptor.
  size_t ByDescriptor() const;

  estimator::LoopClosure closure_;
  estimator::NowNsFn now_ns_;
  daemon::TimeScale time_;
  std::vector<State> sweeps_;      ///< odometry frame
  std::vector<double> update_ms_;  ///< AddKeyframe calls that verified a candidate
  std::vector<double> graph_ms_;   ///< of those, the ones that optimized
  std::vector<double> gnss_ms_;    ///< AddGnss calls that optimized
};

}  // namespace swlio::tools

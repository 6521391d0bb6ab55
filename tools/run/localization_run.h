#pragma once
/// @file
/// swlio-run's localization in a saved map (`--map FILE --localize`): every keyframe of the
/// odometry goes through MapLocalizer (estimator/map/map_localizer.h); a sweep is written to the
/// trajectory (in the map's frame) once the pose is localized, with the correction known at
/// its time. The summary tells when it was localized, counted from the recording's start.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/estimator/common/stage_timer.h"
#include "swlio/estimator/map/map_localizer.h"

namespace swlio::tools {

class LocalizationRun {
 public:
  /// Loads the map; null with *error when it cannot be read.
  static std::unique_ptr<LocalizationRun> Open(const std::string& map_path,
                                               const estimator::LocalizationConfig& config,
                                               estimator::NowNsFn now_ns,
                                               std::string* error);

  /// Host time at which the recording starts (for "localized after").
  void SetStart(int64_t t_ns) { start_ns_ = t_ns; }
  /// A tracked sweep's state (odometry frame) and its keyframe (null unless one); true with
  /// the state in the map frame in *out once localized.
  bool OnSweep(const State& odom, const estimator::KeyframeCloud* keyframe, State* out);
  /// `"localization": {...}` for the summary JSON.
  std::string SummaryJson() const;

 private:
  LocalizationRun(estimator::SavedMap map,
                  const estimator::LocalizationConfig& config,
                  estimator::NowNsFn now_ns);

  estimator::MapLocalizer localizer_;
  estimator::NowNsFn now_ns_;
  int64_t start_ns_ = 0;
  size_t map_nodes_ = 0;
  size_t sweeps_out_ = 0;
  std::vector<double> relocalize_ms_;  ///< AddKeyframe calls that relocalized
  std::vector<double> track_ms_;       ///< AddKeyframe calls that tracked
};

}  // namespace swlio::tools

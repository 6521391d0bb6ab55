#include "localization_run.h"

#include <cstdio>
#include <utility>

#include "spread.h"

namespace swlio::tools {

std::unique_ptr<LocalizationRun> LocalizationRun::Open(const std::string& map_path,
                                                       const estimator::LocalizationConfig& config,
                                                       estimator::NowNsFn now_ns,
                                                       std::string* error) {
  std::optional<estimator::SavedMap> map = estimator::LoadMapFile(map_path, error);
  if (!map) return nullptr;
  if (map->file_version == estimator::kSavedMapVersionManualFrame) {
    std::fprintf(stderr,
                 "swlio-run: %s is a version-1 map (LiDAR frame of the RoboSense manual), "
                 "converted to the drivers' frame on reading\n",
                 map_path.c_str());
  }
  return std::unique_ptr<LocalizationRun>(new LocalizationRun(std::move(*map), config, now_ns));
}

LocalizationRun::LocalizationRun(estimator::SavedMap map,
                                 const estimator::LocalizationConfig& config,
                                 estimator::NowNsFn now_ns)
    : localizer_(std::move(map), config), now_ns_(now_ns) {
  map_nodes_ = localizer_.map().nodes.size();
}

bool LocalizationRun::OnSweep(const State& odom,
                              const estimator::KeyframeCloud* keyframe,
                              State* out) {
  if (keyframe != nullptr) {
    const estimator::LocalizationState before = localizer_.state();
    const int64_t t0 = now_ns_ != nullptr ? now_ns_() : 0;
    const estimator::LocalizationUpdate u = localizer_.AddKeyframe(*keyframe);
    const double ms = now_ns_ != nullptr ? static_cast<double>(now_ns_() - t0) * 1e-6 : 0.0;
    if (u.registrations > 0) {
      (before == estimator::LocalizationState::kRelocalizing ? relocalize_ms_ : track_ms_)
          .push_back(ms);
    }
  }
  if (!localizer_.localized()) return false;
  *out = odom;
  out->T_world_imu = localizer_.T_map_odom() * odom.T_world_imu;
  out->vel_world = localizer_.T_map_odom().linear() * odom.vel_world;
  ++sweeps_out_;
  return true;
}

std::string LocalizationRun::SummaryJson() const {
  const estimator::LocalizationStats& s = localizer_.stats();
  const double localized_after_s =
      s.first_localized_t_ns < 0 ? -1.0
                                 : static_cast<double>(s.first_localized_t_ns - start_ns_) * 1e-9;
  const auto reloc = Spread(relocalize_ms_);
  const auto track = Spread(track_ms_);
  char json[1024];
  std::snprintf(json, sizeof json,
                "\"localization\": {\"map_nodes\": %zu, \"localized_after_s\": %.2f, "
                "\"state\": \"%s\", \"sweeps_localized\": %zu, \"keyframes\": %zu, "
                "\"relocalization_tries\": %zu, \"relocalization_registrations\": %zu, "
                "\"ambiguous\": %zu, \"hypotheses\": %zu, "
                "\"hypotheses_dropped\": %zu, \"tracked\": %zu, \"track_failures\": %zu, "
                "\"lost\": %zu, \"relocalize_ms\": [%.2f, %.2f, %.2f], "
                "\"track_ms\": [%.2f, %.2f, %.2f]}",
                map_nodes_, localized_after_s, estimator::ToString(localizer_.state()), sweeps_out_,
                s.keyframes, s.relocalization_tries, s.relocalization_registrations, s.ambiguous,
                s.hypotheses, s.hypotheses_dropped, s.tracked, s.track_failures, s.lost, reloc[0],
                reloc[1], reloc[2], track[0], track[1], track[2]);
  return json;
}

}  // namespace swlio::tools

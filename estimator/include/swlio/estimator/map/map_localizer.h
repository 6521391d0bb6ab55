#pragma once
/// @file
/// Localization in a saved map (issue 8; `swliod --map FILE --localize`). The window estimator
/// runs as always and gives odometry in its own world ("odom"); this class finds and keeps
/// T_map_odom, so that the output T_map_odom · T_odom_imu lies in the saved map's frame.
///
/// - Relocalizing (nothing known): a keyframe every `relocalize_every_m` has its descriptor
///   compared with every map node's (scan_context.h); the nearest few are verified by registration
///   against the submap around their node, starting from the pose the match implies
///   (keyframe_descriptor.h). The best accepted one becomes a hypothesis, unless one elsewhere fits
///   about as well (a look-alike bay): then a later keyframe tries again.
/// - Confirming: the following keyframes are registered against the map from the pose the
///   hypothesis predicts; `confirmations` agreeing in a row make it trusted, one failure drops
///   it (a look-alike place does not survive the next metres).
/// - Tracking: a keyframe every `track_every_m` is registered against the map nodes around
///   its predicted pose and T_map_odom is updated to it; failures leave T_map_odom as it was
///   (the odometry carries the pose through a changed or unmapped stretch), and after
///   `lost_after_failures` in a row the pose is lost and relocalization starts again.
/// - A hint (an operator's "the robot is here": rviz2's /initialpose, `swlioctl relocalize`):
///   ApplyHint registers the newest keyframe from the hinted pose, and from descriptor matches
///   within the hint's uncertainty, and takes the best fit there. It is refused when no map lies
///   near the hint, when nothing there fits, or when the scan fits a place outside the hint's
///   uncertainty clearly better (ApplyHint runs the global search too); a fit about as good
///   elsewhere (a look-alike bay) leaves the hypothesis to be confirmed as a descriptor one is.
/// The map itself is never changed. Pure library: the daemon runs it in its own thread.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "swlio/estimator/common/keyframe_cloud.h"
#include "swlio/estimator/loop/loop_verifier.h"
#include "swlio/estimator/loop/scan_context.h"
#include "swlio/estimator/map/localization_config.h"
#include "swlio/estimator/map/saved_map.h"

namespace swlio::estimator {

enum class LocalizationState { kRelocalizing, kConfirming, kTracking };

const char* ToString(LocalizationState state);

struct LocalizationUpdate {
  int registrations = 0;  ///< registrations run for this keyframe
  bool accepted = false;  ///< one of them was accepted
  size_t map_node = 0;    ///< the node registered against (of the accepted one, or the last)
  LoopCheck check;        ///< valid when registrations > 0
  LocalizationState state = LocalizationState::kRelocalizing;  ///< after this keyframe
};

/// Where an operator says the robot's IMU is (the daemon turns a base_link pose into this).
/// The height and the tilt are not given: the height is the nearest map node's, the tilt the
/// odometry's (both frames are gravity-aligned).
struct LocalizationHint {
  double x_m = 0.0;  ///< IMU position in the map
  double y_m = 0.0;
  double yaw_rad = 0.0;  ///< azimuth of the IMU's x axis in the map
  /// 1σ of the hint (rviz2's "2D Pose Estimate" sends 0.5 m and 0.26 rad): fits are sought
  /// within 3σ of it.
  double sigma_xy_m = 0.5;
  double sigma_yaw_rad = 0.26;
};

enum class HintVerdict {
  kTracking,    ///< fitted where hinted, nowhere else as well: localized
  kConfirming,  ///< fitted where hinted, about as well as elsewhere: the next keyframes decide
  kNoMap,       ///< no map node within the search radius of the hint
  kNoFit,       ///< the scan does not register near the hint
  kElsewhere,   ///< the scan fits a place outside the hint's uncertainty clearly better
  kNoKeyframe,  ///< no keyframe yet to register (the estimator has not started)
};
const char* ToString(HintVerdict verdict);

struct HintOutcome {
  HintVerdict verdict = HintVerdict::kNoKeyframe;
  int registrations = 0;
  size_t map_node = 0;  ///< the node whose submap the best fit registered against
  /// The best fit within the hint's uncertainty (any verdict but kNoMap/kNoKeyframe): its check
  /// and the IMU position it implies.
  LoopCheck check;
  Eigen::Vector3d p_map = Eigen::Vector3d::Zero();
  double yaw_map_rad = 0.0;
  /// kElsewhere: the better place and its fitness; kNoMap: the nearest node's distance.
  Eigen::Vector3d p_elsewhere = Eigen::Vector3d::Zero();
  double fitness_elsewhere = 0.0;
  double nearest_node_m = 0.0;
};

struct LocalizationStats {
  size_t keyframes = 0;
  size_t relocalization_tries = 0;     ///< keyframes whose descriptor was searched
  size_t relocalization_deferred = 0;  ///< keyframes not tried: too close to the last try
  size_t relocalization_registrations = 0;
  size_t hypotheses = 0;          ///< relocalizations accepted
  size_t ambiguous = 0;           ///< keyframes where two places fitted about as well
  size_t hypotheses_dropped = 0;  ///< not confirmed
  size_t tracked = 0;             ///< tracking registrations accepted
  size_t track_failures = 0;
  size_t lost = 0;  ///< times tracking gave up
  int64_t first_localized_t_ns = -1;
  size_t hints = 0;
  size_t hints_refused = 0;
};

class MapLocalizer {
 public:
  /// `map` must have descriptors made as its header says (ReadSavedMap checks the sizes).
  MapLocalizer(SavedMap map, const LocalizationConfig& config);

  /// Offers an odometry keyframe (time order).
  LocalizationUpdate AddKeyframe(const KeyframeCloud& keyframe);

  /// An operator's hint, applied to `keyframe` (the newest one the caller has; the hint is taken
  /// as its pose). Replaces the current hypothesis or track unless refused; a refusal leaves
  /// the state as it was.
  HintOutcome ApplyHint(const KeyframeCloud& keyframe, const LocalizationHint& hint);

  bool localized() const { return state_ == LocalizationState::kTracking; }
  LocalizationState state() const { return state_; }
  /// The odometry-to-map correction (identity until a first hypothesis).
  const Eigen::Isometry3d& T_map_odom() const { return T_map_odom_; }
  const LocalizationStats& stats() const { return stats_; }
  const SavedMap& map() const { return map_; }

 private:
  LocalizationUpdate Relocalize(const KeyframeCloud& keyframe);
  LocalizationUpdate Track(const KeyframeCloud& keyframe);
  /// The best matches, one per place, at most relocalize_candidates.
  std::vector<std::pair<size_t, ScanContextMatch>> DistinctPlaces(
      const std::vector<std::pair<size_t, ScanContextMatch>>& matches) const;
  /// The best accepted registration of `keyframe` within the hint's 3σ: from the hinted pose,
  /// then from descriptor matches of nodes near it.
  /// `matches`: the keyframe's DistinctPlaces.
  HintOutcome FitNearHint(const KeyframeCloud& keyframe,
                          const LocalizationHint& hint,
                          const std::vector<std::pair<size_t, ScanContextMatch>>& matches);
  /// Registers `keyframe` against node `node`'s submap from the map pose `T_map_imu_guess`,
  /// allowing a correction of `max_m` / `max_rad`.
  LoopCheck RegisterFrom(const KeyframeCloud& keyframe,
                         size_t node,
                         const Eigen::Isometry3d& T_map_imu_guess,
                         double max_m,
                         double max_rad) const;
  bool DueForTracking(const KeyframeCloud& keyframe) const;
  bool DueForRelocalization(const KeyframeCloud& keyframe) const;
  /// Back to global relocalization; the next keyframe tries at once.
  void StartRelocalizing();
  /// Map nodes within submap_radius_m of `p_map`, nearest first, at most submap_max_nodes.
  std::vector<size_t> NodesNear(const Eigen::Vector3d& p_map) const;
  LoopSubmap BuildSubmap(size_t center, const std::vector<size_t>& nodes) const;
  LoopCheck Register(const KeyframeCloud& keyframe,
                     size_t center,
                     const Eigen::Isometry3d& T_center_lidar_guess,
                     bool relocalizing) const;
  void Accept(const KeyframeCloud& keyframe, size_t node, const LoopCheck& check);

  SavedMap map_;
  LocalizationConfig config_;
  ScanContextConfig descriptor_config_;
  ScanContextDatabase descriptors_;
  LocalizationState state_ = LocalizationState::kRelocalizing;
  Eigen::Isometry3d T_map_odom_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_odom_imu_last_registered_ = Eigen::Isometry3d::Identity();
  /// The last relocalization try's pose; none since relocalizing (re)started.
  std::optional<Eigen::Isometry3d> T_odom_imu_last_try_;
  int confirmed_ = 0;
  int failures_ = 0;
  LocalizationStats stats_;
};

}  // namespace swlio::estimator

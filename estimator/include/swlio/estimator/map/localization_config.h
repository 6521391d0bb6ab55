#pragma once
/// @file
/// Options of localization in a saved map (map_localizer.h), apart from it so that
/// configuration code does not pull in Ceres.

#include "swlio/core/config_issue.h"
#include "swlio/estimator/loop/loop_closure_config.h"

namespace swlio::estimator {

struct LocalizationConfig {
  /// Registration and its acceptance tests (matcher settings, submap voxels, inlier distance,
  /// fitness, inliers, Hessian): the loop verifier's (loop_verifier.h). Its max_correction_*
  /// are replaced by the two bounds below, one per mode.
  LoopClosureConfig registration;
  /// Global relocalization (no pose known): every map node's descriptor is compared in full
  /// (~30 µs each) and those nearer than this ...
  double relocalize_max_descriptor_distance = 0.5;
  /// ... are verified, best first, one per place (nodes within 2·distinct_m of a better one
  /// are skipped), this many places per keyframe, each from the pose its match implies.
  int relocalize_candidates = 8;
  /// A descriptor match says nothing of the offset between the two places (its rings are
  /// 3 m wide) and gives the yaw to a sector (6°): registration may move that guess this far.
  double relocalize_max_correction_m = 6.0;
  double relocalize_max_correction_rad = 0.35;
  /// Look-alike places (a substation repeats its bays every few tens of metres) register
  /// almost as well as the true one: a hypothesis is taken only when its fitness beats every
  /// accepted one more than `distinct_m` away by this much; otherwise the next keyframe tries
  /// again. Where the scene changed since mapping (vehicles moved) the true place loses fitness
  /// too: at 0.05, `revisit` seed 2 (people and vehicles) in `field` 1's map took a bay 56 m
  /// away, and two confirmations (six as well) did not drop it; it tracked there for 65 s.
  double relocalize_min_margin = 0.10;
  double distinct_m = 3.0;
  /// While relocalizing, a keyframe is tried after this much motion since the last try (the
  /// first keyframe, and the first after a dropped or lost pose, at once): a try verifies up
  /// to relocalize_candidates places (~110 ms on loop943's map), and trying every window
  /// keyframe (about five a second) on a long ambiguous stretch would take more than half a
  /// core and back up the daemon's keyframe queue. A place ambiguous here is rarely told
  /// apart a few decimetres on.
  double relocalize_every_m = 1.0;
  double relocalize_every_rad = 0.2;
  /// A relocalization is trusted (localized() true) once this many tracking registrations in
  /// a row have agreed with it; until then a failed one drops the hypothesis.
  int confirmations = 2;
  /// While tracking, a keyframe is registered after this much motion since the last one (the
  /// keyframes in between follow the odometry); every keyframe is while confirming.
  double track_every_m = 0.5;
  double track_every_rad = 0.1;
  /// The submap a keyframe is registered against: the map nodes within this distance of the
  /// place, at most this many (the nearest). Wide, so that it covers what the sensor sees and
  /// a look-alike bay's neighbours count against it.
  double submap_radius_m = 30.0;
  int submap_max_nodes = 60;
  /// Planar features on their planes needed while tracking (the loop verifier's min_fitness is
  /// for a place seen anew; a mapped place may have changed since: parked vehicles, new
  /// equipment, vegetation).
  double track_min_fitness = 0.35;
  /// Drift between two keyframes is centimetres: a tracking correction beyond this is wrong.
  double track_max_correction_m = 1.0;
  double track_max_correction_rad = 0.1;
  /// After this many failed tracking registrations in a row the pose is considered lost and
  /// global relocalization starts again (the odometry carries the pose meanwhile).
  int lost_after_failures = 30;

  ConfigIssues Validate() const;
};

}  // namespace swlio::estimator

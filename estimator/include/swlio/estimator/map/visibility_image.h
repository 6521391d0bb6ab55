#pragma once
/// @file
/// Free space seen by one keyframe, for removing moving objects (people, vehicles) from the
/// maps: a coarse range image of the keyframe's whole de-skewed sweep (rings × azimuth bins,
/// the nearest return per cell) at its world pose, and the test of a map point against it.
///
/// The test (visibility-based removal, as in Kim & Kim, "Remove, then Revert", IROS 2020, and
/// Pomerleau et al., "Long-term 3D map maintenance in dynamic environments", ICRA 2014): a
/// map point whose direction lies on one of the keyframe's beams (within `beam_tolerance_m`
/// across the beam) is
///  - seen through when every return of that ring in the columns around it is farther than the
///    point by the margin: the beam went through the place the point occupied;
///  - confirmed when the nearest of them is at the point's own range (within the margin);
///  - unknown otherwise (occluded by something nearer, no return around it, off every beam,
///    or outside [min_range_m, max_range_m]).
/// The margin grows with range (margin_m + margin_ratio · range) and with the range's slope
/// across rings at that column times the point's angle off the beam: a beam grazing the ground
/// lands metres farther for a tenth of a degree, which is no evidence of free space.
///
/// Built once per keyframe (one pass over the sweep), then read-only: copies may be shared
/// between threads.

#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"

namespace swlio::estimator {

struct VisibilityConfig {
  /// Off: maps keep every point (the behaviour before issue 36).
  bool enabled = true;
  int64_t rings = 16;     ///< rows; a point's ring must be below this
  int64_t columns = 900;  ///< azimuth bins per turn (0.4°: two RS16 columns at 10 Hz)
  double min_range_m = 1.0;
  double max_range_m = 60.0;  ///< map points farther from the keyframe are not tested
  /// A point is tested only when the beam of its nearest ring passes within this distance.
  double beam_tolerance_m = 0.1;
  /// A return counts as behind a point beyond margin_m + margin_ratio · range (+ the slope
  /// term above), and as the point itself within margin_m + margin_ratio · range.
  double margin_m = 0.3;
  double margin_ratio = 0.02;
  /// Columns on each side of the point's own that must see through too (at least this many;
  /// more where the beam tolerance spans more columns).
  int64_t neighbour_columns = 1;
  /// A map point leaves the map after this many seen-through tests with no confirmation in
  /// between (a confirmation starts the count again). The window's keyframes are 0.2 m apart:
  /// with 2, the local map lost 2.1 % of its static points on `short` with the simulator's
  /// actors (tests/estimator/loop/loop_closure_visibility_test.cpp), with 3 1.7 %, movers
  /// 0.56 % → 0.74 % of it. Loop closure's nodes are 1 m apart and keep their own count
  /// (MapVisibilityConfig, 2).
  int64_t votes_to_remove = 3;
  /// Keyframes test the map points within this distance of the robot.
  double check_radius_m = 40.0;

  ConfigIssues Validate() const;
};

enum class Visibility : uint8_t { kUnknown, kSeenThrough, kConfirmed };

/// The running score of one map point: consecutive seen-through tests (a confirmation resets
/// it). Returns the new score.
inline int8_t UpdateScore(int8_t score, Visibility v) {
  if (v == Visibility::kConfirmed) return 0;
  if (v == Visibility::kSeenThrough && score < INT8_MAX) return static_cast<int8_t>(score + 1);
  return score;
}

class VisibilityImage {
 public:
  explicit VisibilityImage(const VisibilityConfig& config);

  /// Projects a de-skewed sweep (LiDAR frame at `T_world_lidar`); replaces the previous image.
  void Build(std::span<const LidarPoint> points_lidar, const Eigen::Isometry3d& T_world_lidar);

  /// The test above for a world point.
  Visibility Test(const Eigen::Vector3d& p_world) const;

  const Eigen::Isometry3d& T_world_lidar() const { return T_world_lidar_; }
  /// Heap bytes held (the image and the ring table).
  size_t bytes() const {
    return range_cm_.capacity() * sizeof(uint16_t) + ring_elevation_rad_.capacity() * 5;
  }

 private:
  /// Range of a cell in metres, 0 when it had no return.
  float RangeAt(int ring, int column) const {
    return static_cast<float>(range_cm_[static_cast<size_t>(ring) * static_cast<size_t>(columns_) +
                                        static_cast<size_t>(column)]) *
           0.01f;
  }
  int NearestRing(float elevation_rad) const;
  /// Range slope across rings at `column` around `ring` (m/rad), or < 0 when unknown.
  float SlopeAt(int ring, int column) const;

  VisibilityConfig config_;
  int rings_;
  int columns_;
  Eigen::Isometry3d T_world_lidar_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_lidar_world_ = Eigen::Isometry3d::Identity();
  /// Nearest return per cell in centimetres (to 655 m), 0 = none: half the bytes of a float,
  /// for the keyframes queued to loop closure (up to 256 in swliod, 29 kB each).
  std::vector<uint16_t> range_cm_;
  /// Mean elevation of each ring's returns (rad), and whether it had any.
  std::vector<float> ring_elevation_rad_;
  std::vector<uint8_t> ring_seen_;
};

}  // namespace swlio::estimator

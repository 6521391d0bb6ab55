#pragma once
/// @file
/// Point-cloud segmentation of paper §4.1 (after LeGO-LOAM): ground from the slope between
/// vertically adjacent rings of the range image, then breadth-first clustering of the rest with
/// the angle criterion β of eq. (13); small clusters are outliers. The output keeps ground and
/// accepted clusters, ring by ring in column order, for feature extraction. Unlike LeGO-LOAM,
/// a ground pair may skip rings that have no return in the column (see
/// SegmentationConfig::ground_max_missing_rings).

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"
#include "swlio/estimator/frontend/range_image.h"

namespace swlio::estimator {

struct SegmentationConfig {
  RangeImageConfig image;
  /// Ground is tested between rings r and r+1 for r < ground_max_ring (RS16: rings 0–7 look
  /// down, so 7 tests every downward pair).
  int64_t ground_max_ring = 7;
  /// A ring pair is also formed across up to this many rings without a return in the column
  /// (no echo from dark, wet or mirror-like ground). With adjacent pairs only, a lost return
  /// also took the ground label of a neighbour whose only pair it was: on `aggressive` with
  /// the simulator's dropouts, ~160 ground returns per sweep (1.5 %) became outliers.
  int64_t ground_max_missing_rings = 2;
  double ground_max_slope_deg = 10.0;  ///< slope of a ring pair below which both are ground
  /// A ground candidate with the next ring above it horizontally this close and rising
  /// steeply is the foot of a wall, not ground (0 disables the test).
  double ground_foot_gap_m = 0.15;
  /// LiDAR tilt against the robot's ground plane (R = Ry(pitch)·Rx(roll) levels the LiDAR
  /// frame), so that a tilted mount does not eat into the slope threshold.
  double mount_roll_deg = 0.0;
  double mount_pitch_deg = 0.0;
  /// β of eq. (13) above which two neighbouring cells belong to one object.
  double cluster_angle_deg = 60.0;
  int64_t min_cluster_points = 30;  ///< clusters this large are always kept
  /// Smaller clusters are kept when they span this many rings (a pole, a thin mast)...
  int64_t min_cluster_rings = 5;
  int64_t min_spanning_cluster_points = 5;  ///< ...and have at least this many points

  ConfigIssues Validate() const;
};

/// Per-point labels: ground, outlier, not in the image, or a cluster id ≥ 1.
inline constexpr int32_t kLabelInvalid = -3;  ///< not projected (range, ring or collision)
inline constexpr int32_t kLabelOutlier = -2;  ///< in a rejected (small) cluster
inline constexpr int32_t kLabelGround = -1;

/// One point of the segmented cloud.
struct SegmentedPoint {
  Eigen::Vector3f xyz_m = Eigen::Vector3f::Zero();
  float range_m = 0.0f;
  int64_t dt_ns = 0;
  uint32_t source_index = 0;  ///< index in the input scan
  int32_t label = kLabelInvalid;
  uint16_t ring = 0;
  uint16_t column = 0;
};

struct SegmentationResult {
  std::vector<int32_t> labels;         ///< one per input point
  std::vector<SegmentedPoint> points;  ///< ground + kept clusters, ring-major, column order
  std::vector<uint32_t> ring_begin;    ///< points of ring r: [ring_begin[r], ring_begin[r+1])
  RangeImageStats image;
  int64_t ground_points = 0;
  int64_t clusters = 0;  ///< kept clusters
  int64_t outlier_points = 0;
};

/// Holds every buffer; after the first scan of a given size, `Segment` does not allocate.
class Segmenter {
 public:
  explicit Segmenter(const SegmentationConfig& config);

  /// Levels the ring pairs with the configured mount tilt.
  void Segment(const Scan& scan, SegmentationResult* result);
  /// Levels the ring pairs with `R_level_lidar` for this scan instead (for example roll and
  /// pitch of the current attitude, from gravity), so that slopes are taken against gravity.
  void Segment(const Scan& scan, const Eigen::Matrix3f& R_level_lidar, SegmentationResult* result);

 private:
  void MarkGround();
  void UnmarkWallFeet(int column);
  void Cluster();
  /// Grows one cluster from `seed` by BFS; returns its cells in queue_[0, size).
  int Grow(int seed, int32_t label, uint64_t* ring_mask);
  bool SameObject(int cell_a, int cell_b) const;
  void Collect(const Scan& scan, SegmentationResult* result) const;

  SegmentationConfig config_;
  RangeImage image_;
  Eigen::Matrix3f R_level_lidar_mount_;
  Eigen::Matrix3f R_level_lidar_;  ///< the one used for the current scan
  float tan_ground_;
  float tan_cluster_;
  float foot_gap_m_;
  std::vector<int32_t> cell_label_;  ///< 0 = unlabelled
  std::vector<int32_t> queue_;
  int32_t clusters_ = 0;
  int64_t outliers_ = 0;
};

}  // namespace swlio::estimator

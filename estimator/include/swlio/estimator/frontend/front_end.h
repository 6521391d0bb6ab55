#pragma once
/// @file
/// The LiDAR front end after de-skew, in its fixed order: segmentation (paper §4.1) → LOAM
/// features → voxel filter (eqs. (14)–(16) or fixed cells) of the edge and planar sets. One
/// object per LiDAR, reused scan after scan (allocation-free after the first sweeps).

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"
#include "swlio/estimator/frontend/feature_extractor.h"
#include "swlio/estimator/frontend/segmentation.h"
#include "swlio/estimator/frontend/voxel_filter.h"

namespace swlio::estimator {

struct FrontEndConfig {
  SegmentationConfig segmentation;
  FeatureConfig features;
  /// Fixed voxel sides for the two feature sets (EstimatorConfig's plane_voxel_m and
  /// edge_voxel_m); 0 switches that set to the adaptive cell of eq. (14) with `adaptive`.
  double plane_voxel_m = 0.4;
  double edge_voxel_m = 0.2;
  VoxelFilterConfig adaptive;

  ConfigIssues Validate() const;
};

struct FrontEndOutput {
  SegmentationResult segmentation;
  FeatureSet features;  ///< edges and planes after the voxel filter
  VoxelFilterResult plane_filter;
  VoxelFilterResult edge_filter;
};

class FrontEnd {
 public:
  explicit FrontEnd(const FrontEndConfig& config);

  /// `scan` must be de-skewed (all points in one LiDAR frame).
  void Process(const Scan& scan, FrontEndOutput* out);

 private:
  FrontEndConfig config_;
  Segmenter segmenter_;
  FeatureExtractor extractor_;
  VoxelFilter filter_;
};

}  // namespace swlio::estimator

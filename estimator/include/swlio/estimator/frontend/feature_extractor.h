#pragma once
/// @file
/// LOAM features on the segmented cloud (paper §4, after LOAM and LeGO-LOAM): smoothness along
/// each ring over ±W neighbours, per-sector selection of edge points (largest smoothness, never
/// ground) and planar points (smallest), with occluded and beam-parallel points rejected and
/// the neighbours of every selected point suppressed. Ground points always feed the planar set.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/estimator/frontend/segmentation.h"

namespace swlio::estimator {

struct FeatureConfig {
  int64_t half_window = 5;  ///< W: neighbours on each side for the smoothness
  int64_t sectors_per_ring = 6;
  /// Smoothness c = (Σ_{j≠i} r_j − 2W·r_i)² in m² (LeGO-LOAM's range form). The RS16's 2 cm
  /// range noise alone gives c ≈ (2W + 4W²)·σ² ≈ 0.044 m² on a plane facing the beam (χ²₁
  /// scaled), so LeGO-LOAM's 0.1 lets ~13 % of plane points through and the per-sector top
  /// picks fill with noise; 0.3 (≈ 6.8× the noise level, P ≈ 1 %) measured 65–95 % of edges on
  /// truly bent geometry in the simulator against ~40 % at 0.1.
  double edge_threshold_m2 = 0.3;
  double planar_threshold_m2 = 0.1;
  int64_t max_sharp_edges_per_sector = 2;
  int64_t max_edges_per_sector = 20;  ///< the sharp ones included
  int64_t max_flat_planes_per_sector = 4;
  double occlusion_jump_m = 0.3;      ///< range step between ring neighbours that occludes
  double parallel_beam_ratio = 0.02;  ///< both neighbour steps > ratio·r: surface ∥ beam
  /// A point on the near side of an occlusion jump that lies off the line through the next two
  /// points inward on its ring, on its own surface (their range extrapolated along the ring to
  /// the point), by more than this (m; 0: off) is taken for a mixed pixel: the beam's footprint
  /// straddled the edge and the return landed between the two surfaces, nearer the near one
  /// (returns merge weighted by power ∝ 1/r²).
  /// LOAM's occlusion test keeps it as the near surface's edge point, so it becomes an edge
  /// feature behind the true edge. 0.15 m would be 3σ of the second range difference with the
  /// RS-LiDAR-16's 2 cm range noise (σ·√6 = 0.05 m). Off: measured (issue 36, bench/README
  /// "The field"), 0.15 m also takes true edge points on sweeps without mixed pixels (5–36 points
  /// a sweep in the simulator, 0–2 of 61–91 edge features, on poles and gantry members), and made
  /// `field` 1–3 worse (3 draws each: 0.0311 / 0.0438 / 0.0352 m against 0.0294 / 0.0320 / 0.0326
  /// m) and the time-offset recordings, which have no mixed pixels, 3 % worse; `loop943` 2 with
  /// mixed pixels alone went from 0.0418 to 0.0305 m (one draw). On the real RS-LiDAR-16 capture it
  /// takes 33 points in 39 sweeps.
  double mixed_pixel_tolerance_m = 0.0;
  int64_t max_neighbour_column_gap = 10;  ///< larger gaps end a neighbourhood

  ConfigIssues Validate() const;
};

struct FeaturePoint {
  Eigen::Vector3f xyz_m = Eigen::Vector3f::Zero();  ///< LiDAR frame of the scan
  int64_t dt_ns = 0;                                ///< after the scan's t_start_ns
  float curvature = 0.0f;                           ///< smoothness c, m²
  uint32_t source_index = 0;                        ///< index in the input scan
  uint16_t ring = 0;
};

struct FeatureSet {
  std::vector<FeaturePoint> edges_sharp;  ///< ≤ max_sharp_edges_per_sector per sector
  std::vector<FeaturePoint> edges;        ///< ≤ max_edges_per_sector per sector (⊇ sharp)
  std::vector<FeaturePoint> planes_flat;  ///< ≤ max_flat_planes_per_sector per sector
  std::vector<FeaturePoint> planes;       ///< every other smooth or ground point (⊇ flat)
  int64_t occluded = 0;                   ///< points rejected by the occlusion test
  int64_t parallel = 0;                   ///< points rejected as beam-parallel
  int64_t mixed = 0;                      ///< points rejected as mixed pixels

  void Clear();
};

/// Holds its buffers; after the first scan of a given size, `Extract` does not allocate.
class FeatureExtractor {
 public:
  explicit FeatureExtractor(const FeatureConfig& config) : config_(config) {}

  void Extract(const SegmentationResult& segmented, FeatureSet* out);

 private:
  void ComputeSmoothness(const SegmentationResult& s, size_t begin, size_t end);
  void RejectUnreliable(const SegmentationResult& s, size_t begin, size_t end, FeatureSet* out);
  /// `edge` off the range line through `inner` and `inner2` by more than the mixed-pixel
  /// tolerance (FeatureConfig::mixed_pixel_tolerance_m).
  bool OffItsSurface(const SegmentationResult& s, size_t edge, size_t inner, size_t inner2) const;
  void SelectSector(const SegmentationResult& s, size_t begin, size_t end, FeatureSet* out);
  void Suppress(const SegmentationResult& s, size_t i);

  FeatureConfig config_;
  size_t ring_begin_ = 0;  ///< the ring being processed: [ring_begin_, ring_end_)
  size_t ring_end_ = 0;
  std::vector<float> curvature_;
  std::vector<uint8_t> flags_;
  std::vector<uint64_t> order_;  ///< per sector: (smoothness bits << 32) | point index
};

}  // namespace swlio::estimator

#pragma once
/// @file
/// Voxel down-sampling of paper §4.2, steps (1)–(5), eqs. (14)–(16): the grid is anchored at
/// the bounding box's minimum corner; its cell side follows from k points per voxel over the
/// box (eq. (14)); each occupied voxel keeps the input point nearest its centroid (eq. (16)),
/// so every output point is a real measurement. A fixed-cell variant anchors the grid at the
/// frame origin instead, so that cells agree from scan to scan.

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "swlio/core/config_issue.h"

namespace swlio::estimator {

struct VoxelFilterConfig {
  double points_per_voxel = 8.0;  ///< k of eq. (14)
  /// Bounds on the adaptive cell side (the paper has none: a sparse or flat cloud would give
  /// an arbitrarily large or zero cell). Box extents below min_cell_m count as min_cell_m.
  double min_cell_m = 0.05;
  double max_cell_m = 5.0;

  ConfigIssues Validate() const;
};

/// What one filtering did.
struct VoxelFilterResult {
  double cell_m = 0.0;
  Eigen::Vector3i grid = Eigen::Vector3i::Zero();  ///< M, N, L of eq. (15) (adaptive only)
  size_t input_points = 0;
  size_t voxels = 0;  ///< occupied voxels = output points
};

/// Eq. (14): cell = ∛(k·l_x·l_y·l_z / n), extents first raised to `min_extent_m`.
double AdaptiveCellSize(const Eigen::Vector3f& extent_m, size_t n, double k, double min_extent_m);

/// Holds its buffers; after the first call of a given size, filtering does not allocate.
class VoxelFilter {
 public:
  /// Eqs. (14)–(16) on `points`; `kept` receives the indices of the representatives in
  /// voxel order (z slowest, x fastest: a deterministic order).
  VoxelFilterResult FilterAdaptive(std::span<const Eigen::Vector3f> points,
                                   const VoxelFilterConfig& config,
                                   std::vector<uint32_t>* kept);

  /// Fixed cell side, grid anchored at the origin; same representative rule.
  VoxelFilterResult FilterFixed(std::span<const Eigen::Vector3f> points,
                                double cell_m,
                                std::vector<uint32_t>* kept);

  /// Either variant applied in place to any point type with an `xyz_m` member (Eigen::Vector3f);
  /// the survivors keep their input order.
  template <typename Point>
  VoxelFilterResult Apply(std::vector<Point>* points, const VoxelFilterConfig& config) {
    Gather(*points);
    return Compact(FilterAdaptive(positions_, config, &kept_), points);
  }
  template <typename Point>
  VoxelFilterResult Apply(std::vector<Point>* points, double cell_m) {
    Gather(*points);
    return Compact(FilterFixed(positions_, cell_m, &kept_), points);
  }

 private:
  VoxelFilterResult Run(std::span<const Eigen::Vector3f> points,
                        const Eigen::Vector3f& origin,
                        double cell_m,
                        std::vector<uint32_t>* kept);
  void SortByVoxel(std::span<const Eigen::Vector3f> points,
                   const Eigen::Vector3f& origin,
                   double cell_m);

  template <typename Point>
  void Gather(const std::vector<Point>& points) {
    positions_.clear();
    for (const Point& p : points) positions_.push_back(p.xyz_m);
  }
  template <typename Point>
  VoxelFilterResult Compact(const VoxelFilterResult& result, std::vector<Point>* points) {
    // Ascending indices make the in-place compaction safe (kept_[i] ≥ i); the survivors keep
    // their input order.
    std::sort(kept_.begin(), kept_.end());
    for (size_t i = 0; i < kept_.size(); ++i) (*points)[i] = (*points)[kept_[i]];
    points->resize(kept_.size());
    return result;
  }

  std::vector<Eigen::Array3i> cells_;                   ///< integer voxel coordinates
  std::vector<std::pair<uint64_t, uint32_t>> keyed_;    ///< (voxel key, point index)
  std::vector<std::pair<uint64_t, uint32_t>> scratch_;  ///< radix sort buffer
  std::vector<Eigen::Vector3f> positions_;
  std::vector<uint32_t> kept_;
};

}  // namespace swlio::estimator

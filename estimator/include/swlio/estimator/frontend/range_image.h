#pragma once
/// @file
/// Range image of one de-skewed LiDAR sweep (paper §4.1, LeGO-LOAM style): rows are rings
/// (0 = lowest beam), columns are azimuth bins. The column is computed from the point itself:
/// azimuth clockwise from +x (atan2(−y, x), the drivers' frame: x forward, y left, z up), so
/// column 0 starts behind the sensor and columns grow clockwise seen from above, as the
/// sensor turns.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"

namespace swlio::estimator {

/// atan2(y, x) to |error| < 1e-5 rad (0.0006°), several times cheaper than std::atan2.
float FastAtan2(float y, float x);

struct RangeImageConfig {
  int64_t rings = 16;      ///< rows; a point's `ring` must be below this (≤ 64)
  int64_t columns = 1800;  ///< azimuth bins per turn: 1800 = 0.2° (RS16 at 10 Hz)
  double min_range_m = 0.4;
  double max_range_m = 150.0;

  ConfigIssues Validate() const;
};

/// Counts of one projection.
struct RangeImageStats {
  int64_t placed = 0;        ///< points now in a cell
  int64_t out_of_range = 0;  ///< range outside [min_range_m, max_range_m] or not finite
  int64_t bad_ring = 0;      ///< ring ≥ rings
  /// A point whose cell and both neighbouring columns were taken (the nearer one is kept).
  int64_t collisions = 0;
};

/// Preallocated at construction; `Build` allocates nothing.
class RangeImage {
 public:
  static constexpr int32_t kEmpty = -1;

  explicit RangeImage(const RangeImageConfig& config);

  /// Projects `points` (LiDAR frame, metres). Clears the previous image first.
  RangeImageStats Build(std::span<const LidarPoint> points);

  int rings() const { return rings_; }
  int columns() const { return columns_; }
  int Cell(int ring, int column) const { return ring * columns_ + column; }
  /// Column of a direction, in [0, columns).
  int Column(const Eigen::Vector3f& xyz_m) const;

  /// Source index (into the span given to `Build`) of a cell, or kEmpty.
  int32_t Index(int cell) const { return index_[static_cast<size_t>(cell)]; }
  /// Range of a cell in metres (0 when empty).
  float Range(int cell) const { return range_m_[static_cast<size_t>(cell)]; }
  const Eigen::Vector3f& Xyz(int cell) const { return xyz_m_[static_cast<size_t>(cell)]; }

 private:
  RangeImageConfig config_;
  int rings_;
  int columns_;
  float columns_per_rad_;
  std::vector<int32_t> index_;
  std::vector<float> range_m_;
  std::vector<Eigen::Vector3f> xyz_m_;
};

}  // namespace swlio::estimator

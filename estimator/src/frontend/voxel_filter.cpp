#include "swlio/estimator/frontend/voxel_filter.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace swlio::estimator {
namespace {

constexpr double kMaxCellIndex = 1 << 20;  ///< ±1 M cells per axis; beyond that, clamped

bool LexLess(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

}  // namespace

ConfigIssues VoxelFilterConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "points_per_voxel", points_per_voxel, 1.0, 1000.0);
  CheckInRange(issues, "min_cell_m", min_cell_m, 0.01, 10.0);
  CheckInRange(issues, "max_cell_m", max_cell_m, 0.01, 100.0);
  CheckThat(issues, min_cell_m <= max_cell_m, "max_cell_m", "must be ≥ min_cell_m");
  return issues;
}

// Eq. (14): with n points and k per voxel, n/k voxels fill the box l_x·l_y·l_z, so
// cell³ = k·l_x·l_y·l_z / n.
double AdaptiveCellSize(const Eigen::Vector3f& extent_m, size_t n, double k, double min_extent_m) {
  if (n == 0) return min_extent_m;
  double volume = 1.0;
  for (int a = 0; a < 3; ++a) volume *= std::max(static_cast<double>(extent_m[a]), min_extent_m);
  return std::cbrt(k * volume / static_cast<double>(n));
}

VoxelFilterResult VoxelFilter::FilterAdaptive(std::span<const Eigen::Vector3f> points,
                                              const VoxelFilterConfig& config,
                                              std::vector<uint32_t>* kept) {
  // Steps (1)–(2): bounding box and its side lengths.
  Eigen::AlignedBox3f box;
  for (const auto& p : points) box.extend(p);
  if (points.empty()) box.extend(Eigen::Vector3f::Zero());
  const Eigen::Vector3f extent = box.sizes();
  const double cell = std::clamp(
      AdaptiveCellSize(extent, points.size(), config.points_per_voxel, config.min_cell_m),
      config.min_cell_m, config.max_cell_m);
  // Steps (4)–(5): the grid anchored at the box minimum, eqs. (15)–(16).
  VoxelFilterResult result = Run(points, box.min(), cell, kept);
  for (int a = 0; a < 3; ++a) {
    result.grid[a] = static_cast<int>(std::floor(static_cast<double>(extent[a]) / cell));
  }
  return result;
}

VoxelFilterResult VoxelFilter::FilterFixed(std::span<const Eigen::Vector3f> points,
                                           double cell_m,
                                           std::vector<uint32_t>* kept) {
  return Run(points, Eigen::Vector3f::Zero(), cell_m, kept);
}

// Eq. (16): voxel (i, j, k) = ⌊(p − p_min)/cell⌋; centroid c_ijk = (1/m)·Σ p over its m points;
// the representative is the point nearest c_ijk (exact ties: the lexicographically smaller
// point, so that the result does not depend on the input order). The sums of floats in double
// are exact, hence order-free too.
VoxelFilterResult VoxelFilter::Run(std::span<const Eigen::Vector3f> points,
                                   const Eigen::Vector3f& origin,
                                   double cell_m,
                                   std::vector<uint32_t>* kept) {
  VoxelFilterResult result;
  result.cell_m = cell_m;
  result.input_points = points.size();
  kept->clear();
  SortByVoxel(points, origin, cell_m);
  for (size_t begin = 0; begin < keyed_.size();) {
    size_t end = begin + 1;
    while (end < keyed_.size() && keyed_[end].first == keyed_[begin].first) ++end;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (size_t j = begin; j < end; ++j) sum += points[keyed_[j].second].cast<double>();
    const Eigen::Vector3d centroid = sum / static_cast<double>(end - begin);
    uint32_t best = keyed_[begin].second;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (size_t j = begin; j < end; ++j) {
      const uint32_t i = keyed_[j].second;
      const double d2 = (points[i].cast<double>() - centroid).squaredNorm();
      if (d2 < best_d2 || (d2 == best_d2 && LexLess(points[i], points[best]))) {
        best_d2 = d2;
        best = i;
      }
    }
    kept->push_back(best);
    begin = end;
  }
  result.voxels = kept->size();
  return result;
}

// Groups the points by voxel: integer cell coordinates, a dense key over their bounding range
// (x fastest, then y, then z), and an LSD radix sort of the (key, index) pairs — O(n) and
// stable, so equal keys keep ascending indices.
void VoxelFilter::SortByVoxel(std::span<const Eigen::Vector3f> points,
                              const Eigen::Vector3f& origin,
                              double cell_m) {
  const double inv_cell = 1.0 / cell_m;
  cells_.clear();
  Eigen::Array3i lo = Eigen::Array3i::Constant(std::numeric_limits<int>::max());
  Eigen::Array3i hi = Eigen::Array3i::Constant(std::numeric_limits<int>::min());
  for (const auto& p : points) {
    Eigen::Array3i c;
    for (int a = 0; a < 3; ++a) {
      const double v = std::floor(static_cast<double>(p[a] - origin[a]) * inv_cell);
      c[a] = static_cast<int>(std::clamp(v, -kMaxCellIndex, kMaxCellIndex));
    }
    lo = lo.min(c);
    hi = hi.max(c);
    cells_.push_back(c);
  }
  keyed_.clear();
  if (points.empty()) return;
  const auto dx = static_cast<uint64_t>(int64_t{hi.x()} - lo.x() + 1);
  const auto dy = static_cast<uint64_t>(int64_t{hi.y()} - lo.y() + 1);
  uint64_t max_key = 0;
  for (size_t i = 0; i < cells_.size(); ++i) {
    const Eigen::Array3i c = cells_[i] - lo;
    const uint64_t key = static_cast<uint64_t>(c.x()) +
                         dx * (static_cast<uint64_t>(c.y()) + dy * static_cast<uint64_t>(c.z()));
    max_key = std::max(max_key, key);
    keyed_.emplace_back(key, static_cast<uint32_t>(i));
  }
  constexpr int kDigitBits = 11;
  constexpr size_t kBuckets = size_t{1} << kDigitBits;
  std::array<uint32_t, kBuckets> count{};
  scratch_.resize(keyed_.size());
  for (int shift = 0; shift < 64 && (max_key >> shift) != 0; shift += kDigitBits) {
    count.fill(0);
    for (const auto& [key, index] : keyed_) ++count[(key >> shift) & (kBuckets - 1)];
    uint32_t total = 0;
    for (auto& c : count) total += std::exchange(c, total);
    for (const auto& entry : keyed_)
      scratch_[count[(entry.first >> shift) & (kBuckets - 1)]++] = entry;
    keyed_.swap(scratch_);
  }
}

}  // namespace swlio::estimator

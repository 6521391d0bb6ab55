#include "swlio/estimator/voxel_map.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace swlio::estimator {

ConfigIssues VoxelMapConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "voxel_m", voxel_m, 0.1, 10.0);
  CheckInRange<size_t>(issues, "max_points_per_voxel", max_points_per_voxel, 1, 1000);
  CheckInRange(issues, "min_point_spacing_m", min_point_spacing_m, 0.0, 5.0);
  CheckInRange(issues, "radius_m", radius_m, 5.0, 1000.0);
  return issues;
}

VoxelMap::VoxelMap(const VoxelMapConfig& config) : config_(config) {}

VoxelMap::Key VoxelMap::KeyOf(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d v = p / config_.voxel_m;
  return {static_cast<int32_t>(std::floor(v.x())), static_cast<int32_t>(std::floor(v.y())),
          static_cast<int32_t>(std::floor(v.z()))};
}

size_t VoxelMap::Insert(const std::vector<Eigen::Vector3d>& points_world) {
  const double min_sq = config_.min_point_spacing_m * config_.min_point_spacing_m;
  size_t stored = 0;
  for (const Eigen::Vector3d& p : points_world) {
    std::vector<Eigen::Vector3d>& voxel = voxels_[KeyOf(p)];
    if (voxel.size() >= config_.max_points_per_voxel) continue;
    const bool crowded = std::any_of(voxel.begin(), voxel.end(), [&](const Eigen::Vector3d& q) {
      return (q - p).squaredNorm() < min_sq;
    });
    if (crowded) continue;
    if (voxel.capacity() == 0) voxel.reserve(config_.max_points_per_voxel);
    voxel.push_back(p);
    ++stored;
  }
  points_ += stored;
  return stored;
}

size_t VoxelMap::Nearest(const Eigen::Vector3d& query,
                         size_t k,
                         double max_distance_m,
                         std::vector<Eigen::Vector3d>* out) const {
  out->clear();
  if (k == 0) return 0;
  const Key c = KeyOf(query);
  const double max_sq = max_distance_m * max_distance_m;
  // Keep the k best (distance², point) in a small sorted buffer.
  std::vector<std::pair<double, const Eigen::Vector3d*>> best;
  best.reserve(k + 1);
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        const auto it = voxels_.find({c.x + dx, c.y + dy, c.z + dz});
        if (it == voxels_.end()) continue;
        for (const Eigen::Vector3d& p : it->second) {
          const double d2 = (p - query).squaredNorm();
          if (d2 > max_sq || (best.size() == k && d2 >= best.back().first)) continue;
          best.insert(std::upper_bound(best.begin(), best.end(), d2,
                                       [](double v, const auto& e) { return v < e.first; }),
                      {d2, &p});
          if (best.size() > k) best.pop_back();
        }
      }
    }
  }
  for (const auto& [d2, p] : best) out->push_back(*p);
  return out->size();
}

size_t VoxelMap::RemoveFar(const Eigen::Vector3d& center_world) {
  const double r2 = config_.radius_m * config_.radius_m;
  size_t removed = 0;
  for (auto it = voxels_.begin(); it != voxels_.end();) {
    const Eigen::Vector3d centre =
        (Eigen::Vector3d(it->first.x, it->first.y, it->first.z) + Eigen::Vector3d::Constant(0.5)) *
        config_.voxel_m;
    if ((centre - center_world).squaredNorm() > r2) {
      removed += it->second.size();
      it = voxels_.erase(it);
    } else {
      ++it;
    }
  }
  points_ -= removed;
  return removed;
}

}  // namespace swlio::estimator

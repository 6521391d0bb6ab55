#pragma once
/// @file
/// What each feature's neighbour search in a VoxelMap found, kept so that the next association
/// of the same features against the same map can skip the search (and the surface fit) for a
/// feature that cannot have found other neighbours. A registration associates one sweep's
/// features 2–4 times at poses millimetres apart, and the window associates them once more.
///
/// When it holds (exact, so the matcher's output does not change). A search from query x found
/// the k nearest points of the 27 voxels around x's voxel, the farthest of them at d_k, and the
/// next one at d_{k+1} (or none: then d_{k+1} is the search's distance bound). Moving the query
/// by δ changes every distance by at most δ, so while x' stays in the same voxel (the same 27
/// cells are searched) and |x' − x| < (d_{k+1} − d_k) / 2, the same k points come out, perhaps
/// in another order; the fit takes them in a fixed order, so it is the same to the last bit.
/// A map that changed (insertion, removal), another map or a feature set of another size
/// forgets everything.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "swlio/estimator/registration/voxel_map.h"

namespace swlio::estimator {

/// One feature's search result: the plane (normal) or line (direction) its neighbours formed.
struct CachedSurface {
  Eigen::Vector3d query_world = Eigen::Vector3d::Zero();  ///< where the search ran
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();         ///< plane normal or line direction
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double margin_m = -1.0;  ///< reusable while the query stays closer than this; < 0: no entry
  bool valid = false;      ///< the neighbours formed a valid surface
};

/// The entries of one feature set against one map.
class NeighbourCacheSet {
 public:
  /// The entries for `features` features against `map`, emptied when the map or the count is
  /// not the one they were made for.
  std::vector<CachedSurface>& For(const VoxelMap& map, size_t features);

 private:
  const VoxelMap* map_ = nullptr;
  uint64_t revision_ = 0;
  std::vector<CachedSurface> entries_;
};

/// A sweep's planar and edge features. Belongs to one ScanMatcher (its validity thresholds
/// decided `valid`) and one feature set (entries are by feature index).
struct NeighbourCache {
  NeighbourCacheSet planes;
  NeighbourCacheSet edges;
};

}  // namespace swlio::estimator

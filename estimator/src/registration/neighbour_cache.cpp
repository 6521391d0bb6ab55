#include "swlio/estimator/registration/neighbour_cache.h"

namespace swlio::estimator {

std::vector<CachedSurface>& NeighbourCacheSet::For(const VoxelMap& map, size_t features) {
  if (map_ != &map || revision_ != map.revision() || entries_.size() != features) {
    map_ = &map;
    revision_ = map.revision();
    entries_.assign(features, CachedSurface{});
  }
  return entries_;
}

}  // namespace swlio::estimator

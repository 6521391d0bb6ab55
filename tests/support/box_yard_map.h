#pragma once
/// @file
/// Test helper: a saved map of the synthetic box yard (box_yard.h), a node every `every` poses
/// of the rectangle drive at its true pose (map = world), with its descriptor; pose k is stamped
/// k × `t_step_ns` (the localization and map tests).

#include "box_yard.h"
#include "swlio/estimator/loop/keyframe_descriptor.h"
#include "swlio/estimator/map/saved_map.h"

namespace swlio::test {

inline estimator::SavedMap BoxYardMap(const Scene& scene, size_t every = 2, int64_t t_step_ns = 1) {
  const estimator::ScanContextConfig d;
  estimator::SavedMap map;
  map.descriptor_rings = d.rings;
  map.descriptor_sectors = d.sectors;
  map.descriptor_max_range_m = d.max_range_m;
  map.descriptor_min_range_m = d.min_range_m;
  map.descriptor_height_offset_m = d.height_offset_m;
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  for (size_t k = 0; k < truth.size(); k += every) {
    const estimator::KeyframeCloud kf = Cut(scene, static_cast<int64_t>(k) * t_step_ns, truth[k]);
    map.nodes.push_back({kf.t_ns, truth[k], kf.T_imu_lidar, kf.planes_lidar, kf.edges_lidar,
                         estimator::KeyframeDescriptor(d, kf).cells});
  }
  return map;
}

}  // namespace swlio::test

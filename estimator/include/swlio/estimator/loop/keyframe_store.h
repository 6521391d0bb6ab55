#pragma once
/// @file
/// The keyframe clouds loop closure keeps (issue 33, memory budget): a graph node's planar and
/// edge features in its LiDAR frame, in float, and only for the nodes that map a place first.
///
/// Float: a saved map stores these points as f32 already (saved_map.h: rounding ≤ 3.8 µm below
/// 128 m), so a map saved from the store is the same file, and a verification submap (1 m
/// voxels, loop_closure_config.h) moves by micrometres. Half the bytes of Eigen::Vector3d.
///
/// Places: a node on a place an older node already holds keeps no cloud (loop_closure.h says
/// when), so a robot patrolling one route keeps one cloud per place, not one per pass.
/// Pure storage; indices are graph node indices, in the order nodes were added.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "swlio/estimator/common/keyframe_cloud.h"

namespace swlio::estimator {

class KeyframeStore {
 public:
  /// Appends node `size()`; its cloud only when `keep_cloud`.
  void Add(const KeyframeCloud& keyframe, bool keep_cloud);

  size_t size() const { return clouds_.size(); }
  bool has_cloud(size_t i) const { return clouds_[i].kept; }
  /// Nodes that keep a cloud.
  size_t clouds() const { return kept_; }
  /// Heap bytes of the stored points (capacity, the node table excluded).
  size_t bytes() const { return bytes_; }

  /// Node i's points moved by `T` (e.g. into a submap's frame), in double.
  std::vector<Eigen::Vector3d> Planes(size_t i, const Eigen::Isometry3d& T) const;
  std::vector<Eigen::Vector3d> Edges(size_t i, const Eigen::Isometry3d& T) const;
  /// `visit(planes_lidar, edges_lidar)` on node i's stored points, without a copy.
  template <typename Fn>
  void Visit(size_t i, Fn&& visit) const {
    visit(clouds_[i].planes_lidar, clouds_[i].edges_lidar);
  }

 private:
  struct Cloud {
    bool kept = false;
    std::vector<Eigen::Vector3f> planes_lidar;
    std::vector<Eigen::Vector3f> edges_lidar;
  };
  std::vector<Cloud> clouds_;
  size_t kept_ = 0;
  size_t bytes_ = 0;
};

}  // namespace swlio::estimator

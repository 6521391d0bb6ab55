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
#include <cstdint>
#include <vector>

#include "swlio/estimator/common/keyframe_cloud.h"
#include "swlio/estimator/map/visibility_image.h"

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
  /// Moving objects out (visibility_image.h): each of node i's points (LiDAR frame, float) is
  /// given to `test` (Eigen::Vector3f → Visibility), its score updated (UpdateScore), and the
  /// point dropped once the score reaches `remove_at`; the others keep their order. Returns
  /// the points dropped.
  template <typename Test>
  size_t VoteAndRemove(size_t i, int remove_at, Test&& test) {
    Cloud& c = clouds_[i];
    return VoteAndRemove(&c.planes_lidar, &c.plane_scores, remove_at, test) +
           VoteAndRemove(&c.edges_lidar, &c.edge_scores, remove_at, test);
  }
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
    std::vector<int8_t> plane_scores, edge_scores;  ///< one per point (visibility_image.h)
  };
  template <typename Test>
  static size_t VoteAndRemove(std::vector<Eigen::Vector3f>* points,
                              std::vector<int8_t>* scores,
                              int remove_at,
                              Test&& test) {
    size_t kept = 0;
    for (size_t j = 0; j < points->size(); ++j) {
      const int8_t score = UpdateScore((*scores)[j], test((*points)[j]));
      if (score >= remove_at) continue;
      (*points)[kept] = (*points)[j];
      (*scores)[kept++] = score;
    }
    const size_t removed = points->size() - kept;
    points->resize(kept);
    scores->resize(kept);
    return removed;
  }
  std::vector<Cloud> clouds_;
  size_t kept_ = 0;
  size_t bytes_ = 0;
};

}  // namespace swlio::estimator

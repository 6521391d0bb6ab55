#pragma once
/// @file
/// The merged map cloud (map_pcd.h: one centroid per voxel of every node's features in the map
/// frame, in voxel order) built from the nodes as the caller holds them, in bounded memory:
/// swliod's map publication copied the loop closure's whole store into a SavedMap in double
/// and sorted one 48-byte record per point every 10 s, its largest transient (issue 33, memory
/// budget).
///
/// The caller feeds every node once per pass:
///
///   MergedCloudBuilder b(voxel_m);
///   while (b.NextPass()) for (node : nodes) b.AddNode(T_map_lidar, planes, edges);
///   return b.Finish(&error);
///
/// The first pass checks the points and counts them per x-cell; each later pass keeps only the
/// points of one stripe of x-cells (at most kMaxRecords of them, unless one x-cell holds more),
/// sorts them and appends the stripe's centroids. Stripes go up in x, so the cloud is in voxel
/// order as a single sort would give; the points of a voxel are summed in input order, so it
/// is the same cloud to the last bit, whatever the stripes.

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace swlio::estimator {

/// A cap on the centroids kept, for a caller that merges again at a larger voxel when the cloud
/// is too big (swliod's map publication): the first `max_points` centroids in voxel order are
/// kept, in a vector reserved once (growing by doubling held 1.5× the cloud at its last step:
/// 16 MB on a 943 m drive's map), and `*total` receives the count of all of them.
struct MergedCloudLimit {
  size_t max_points = std::numeric_limits<size_t>::max();
  size_t* total = nullptr;  ///< if set, every centroid, kept or not
};

class MergedCloudBuilder {
 public:
  /// Points sorted at once at most (56 bytes each): 3.7 MB.
  static constexpr size_t kMaxRecords = 65'536;

  /// `voxel_m` is checked by Finish (finite, ≥ kMergedCloudMinVoxelM).
  explicit MergedCloudBuilder(double voxel_m,
                              size_t max_records = kMaxRecords,
                              MergedCloudLimit limit = {});

  /// Starts the next pass over the nodes; false once the cloud is complete (or refused).
  bool NextPass();

  /// The next node's planar, then edge points (LiDAR frame; Vector3d or Vector3f) moved into
  /// the map frame by T_map_lidar. A point that is not finite or lies beyond
  /// kMergedCloudMaxCoordinateM there makes Finish refuse. Every pass must add the same nodes.
  template <typename Point>
  void AddNode(const Eigen::Isometry3d& T_map_lidar,
               const std::vector<Point>& planes_lidar,
               const std::vector<Point>& edges_lidar) {
    for (const auto* points : {&planes_lidar, &edges_lidar}) {
      for (const Point& p : *points) AddPoint(T_map_lidar * p.template cast<double>());
    }
    ++node_;
  }

  /// The centroids (the first limit.max_points of them), or std::nullopt with *error
  /// ("merged cloud: ...").
  std::optional<std::vector<Eigen::Vector3f>> Finish(std::string* error);

  int passes() const { return pass_; }

 private:
  struct CellPoint {
    std::array<int64_t, 3> cell;
    uint64_t order;  ///< the point's place in the input: the summation order within a voxel
    Eigen::Vector3d p_map;
  };
  bool VoxelOk() const;
  void AddPoint(const Eigen::Vector3d& p_map);
  void PlanStripes();
  void ReduceStripe();

  double voxel_m_;
  size_t max_records_;
  MergedCloudLimit limit_;
  size_t centroids_total_ = 0;
  int pass_ = 0;                                      ///< passes started
  size_t node_ = 0;                                   ///< nodes added in this pass
  uint64_t order_ = 0;                                ///< points added in this pass
  std::string issue_;                                 ///< the first refused point, "" while none
  std::map<int64_t, size_t> per_x_cell_;              ///< first pass: points per x-cell
  std::vector<std::pair<int64_t, int64_t>> stripes_;  ///< [first, last] x-cell of each
  std::vector<CellPoint> points_;                     ///< the current stripe's
  std::vector<Eigen::Vector3f> centroids_;
};

}  // namespace swlio::estimator

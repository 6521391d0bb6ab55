#pragma once
/// @file
/// Incremental voxel-hash local map (in the spirit of Faster-LIO's iVox): world points in cubic
/// voxels, a bounded number per voxel, k-nearest search over the 27 voxels around a query, and
/// removal of voxels far from the robot so memory stays bounded. Chosen over a kd-tree because
/// inserting a scan costs O(points) with no rebuild (design.md: "incremental voxel map").
///
/// Deterministic: results depend only on insertion order, never on hash-table iteration order.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/estimator/map/visibility_image.h"

namespace swlio::estimator {

struct VoxelMapConfig {
  double voxel_m = 1.0;  ///< voxel edge
  size_t max_points_per_voxel = 20;
  double min_point_spacing_m =
      0.1;                 ///< a new point closer than this to one in its voxel is skipped
  double radius_m = 80.0;  ///< voxels farther than this from the robot are dropped

  ConfigIssues Validate() const;
};

class VoxelMap {
 public:
  static constexpr size_t kMaxNeighbours = 32;

  explicit VoxelMap(const VoxelMapConfig& config = {});

  /// Adds world-frame points; returns how many were stored.
  size_t Insert(const std::vector<Eigen::Vector3d>& points_world);

  /// Up to `k` (≤ kMaxNeighbours) nearest stored points within `max_distance_m` of `query`,
  /// nearest first. Searches the query's voxel and its 26 neighbours (cells that cannot hold a
  /// closer point are skipped), so distances beyond one voxel edge may be missed. Writes into
  /// `out` (cleared first); returns the count. No allocation once `out` has capacity k.
  size_t Nearest(const Eigen::Vector3d& query,
                 size_t k,
                 double max_distance_m,
                 std::vector<Eigen::Vector3d>* out) const;

  /// Drops every voxel whose centre is farther than `radius_m` from `center_world`.
  size_t RemoveFar(const Eigen::Vector3d& center_world);

  /// Moving objects out (visibility_image.h): every point of the voxels whose centre lies
  /// within `radius_m` of `center_world` is given to `test` (Eigen::Vector3d → Visibility),
  /// its score updated (UpdateScore), and the point removed once the score reaches
  /// `remove_at`. Returns the points removed. Voxels are visited in creation order and the
  /// survivors keep theirs: deterministic.
  template <typename Test>
  size_t VoteAndRemove(const Eigen::Vector3d& center_world,
                       double radius_m,
                       int remove_at,
                       Test&& test) {
    const double r2 = (radius_m + config_.voxel_m) * (radius_m + config_.voxel_m);
    size_t removed = 0;
    for (uint32_t v = 0; v < voxels_.size(); ++v) {
      Voxel& voxel = voxels_[v];
      if (voxel.count == 0 || (CentreOf(voxel.key) - center_world).squaredNorm() > r2) continue;
      Eigen::Vector3d* points = PointsOf(v);
      int8_t* scores = ScoresOf(v);
      uint32_t kept = 0;
      for (uint32_t i = 0; i < voxel.count; ++i) {
        const int8_t score = UpdateScore(scores[i], test(points[i]));
        if (score >= remove_at) continue;
        points[kept] = points[i];
        scores[kept++] = score;
      }
      removed += voxel.count - kept;
      voxel.count = kept;
    }
    if (removed > 0) Removed(removed);
    return removed;
  }

  /// Every stored point, voxel by voxel in creation order (to carry a map into another frame).
  std::vector<Eigen::Vector3d> Points() const;

  /// Changes whenever the stored points do (Insert, RemoveFar), and differs between maps: a
  /// value unique in the process (NeighbourCache tells a changed map by it).
  uint64_t revision() const { return revision_; }

  /// Whether both points fall into the same voxel.
  bool SameVoxel(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return KeyOf(a) == KeyOf(b);
  }

  size_t size() const { return points_; }
  size_t voxels() const { return voxels_.size(); }

 private:
  struct Key {
    int32_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  static constexpr uint32_t kNoVoxel = UINT32_MAX;
  /// An entry of the index: the key beside its voxel, so that probing past other keys and
  /// missing an empty cell (most of a query's 27) never touch the voxels themselves.
  struct Slot {
    Key key;
    uint32_t voxel = kNoVoxel;  ///< index into voxels_, or kNoVoxel when empty
  };
  struct Voxel {
    Key key;
    uint32_t count = 0;  ///< its points: PointsOf(v)[0], …, PointsOf(v)[count − 1]
  };

  /// The cells around a query nearer than a bound, in search order: each one's key, squared
  /// distance from the query and home slot (whose load has been started).
  struct NearCells {
    std::array<Key, 27> key;
    std::array<double, 27> box_sq;
    std::array<size_t, 27> home;
    size_t size = 0;
  };
  Key KeyOf(const Eigen::Vector3d& p) const;
  Eigen::Vector3d CentreOf(const Key& key) const {
    return (Eigen::Vector3d(key.x, key.y, key.z) + Eigen::Vector3d::Constant(0.5)) *
           config_.voxel_m;
  }
  void Removed(size_t points);  ///< counts and a new revision after VoteAndRemove
  static uint64_t AxisHash(size_t axis, int32_t cell);  ///< one axis's term of a key's hash
  size_t HomeOf(uint64_t hash) const;                   ///< the slot of a key's hash
  size_t Home(const Key& key) const;                    ///< first probe of `key` in slots_
  /// Voxel index of `key`, or kNoVoxel, probing from its home slot (slots_ not empty).
  uint32_t FindFrom(const Key& key, size_t home) const;
  NearCells CellsWithin(const Eigen::Vector3d& query, double bound_sq) const;
  uint32_t FindOrAdd(const Key& key);
  void Reindex(size_t slot_count);
  /// Voxels per pool chunk (below).
  static constexpr uint32_t kChunkVoxels = 512;
  /// Voxel v's points: max_points_per_voxel slots, `count` of them used.
  Eigen::Vector3d* PointsOf(uint32_t voxel) {
    return pool_[voxel / kChunkVoxels].data() +
           size_t{voxel % kChunkVoxels} * config_.max_points_per_voxel;
  }
  const Eigen::Vector3d* PointsOf(uint32_t voxel) const {
    return pool_[voxel / kChunkVoxels].data() +
           size_t{voxel % kChunkVoxels} * config_.max_points_per_voxel;
  }

  /// Voxel v's points' visibility scores (visibility_image.h), beside PointsOf(v).
  int8_t* ScoresOf(uint32_t voxel) {
    return scores_[voxel / kChunkVoxels].data() +
           size_t{voxel % kChunkVoxels} * config_.max_points_per_voxel;
  }

  VoxelMapConfig config_;
  // The voxels in a flat vector (in creation order) indexed by an open-addressing table with
  // linear probing (load ≤ 1/2): a query touches up to 27 cells, and std::unordered_map's
  // modulo and node chasing per lookup had cost more than the distances themselves. Their
  // points sit in one pool, max_points_per_voxel apiece (what each voxel's own vector used to
  // reserve), so a voxel's points are one contiguous read with no pointer to follow. The pool
  // is chunks of kChunkVoxels voxels (issue 33, memory budget): one vector had doubled its
  // capacity as the map grew, held the old and the new array at once while it moved them (the
  // process's peak was that moment), and kept its capacity after RemoveFar.
  std::vector<Voxel> voxels_;
  std::vector<std::vector<Eigen::Vector3d>> pool_;
  std::vector<std::vector<int8_t>> scores_;  ///< chunked as pool_
  std::vector<Slot> slots_;                  ///< size a power of two
  int slot_bits_ = 0;
  size_t points_ = 0;
  uint64_t revision_;
};

}  // namespace swlio::estimator

#pragma once
/// @file
/// The map cloud on DDS (issue 8: "the corrected trajectory and map are published"). A saved
/// map — the pose graph's nodes at their corrected poses while mapping, or the map loaded for
/// localization — is merged into one cloud by estimator::MergedMapCloud (every node's planar
/// and edge features moved into the map frame, one centroid per voxel, the same cloud as the
/// saved map's .pcd), packed as sensor_msgs/PointCloud2 (x, y, z float32, ipc/point_cloud.h)
/// and written on the latched map topic.
///
/// Size cap (`ipc.map_max_points`): by voxel size, so the density stays even. The first build
/// uses kMergedCloudVoxelM (0.1 m); while the cloud has more than `max_points` points the voxel
/// grows, up to kMaxVoxelSteps rebuilds: the count n falls as voxel^−k, k measured from the
/// last two builds (2 for the first step, as on densely sampled surfaces, so that step never
/// coarsens more than needed; ≈ 0.8 on a 943 m drive's map, where most voxels hold one
/// feature point), aiming 5 % below the cap. A cloud still too large after that keeps every
/// k-th point. Each later build starts at the voxel the last one needed (a map only grows), so
/// a large map is usually merged once or twice per publication.
///
/// Thread roles: runs on the thread that owns the map (loop_closure or localization, normal
/// priority), never on the IMU-rate path or the publisher thread; that thread is the only
/// writer of the map topic (Publisher methods are safe per topic). counters() from any thread.

#include <Eigen/Core>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/estimator/map/merged_cloud_builder.h"
#include "swlio/estimator/map/saved_map.h"
#include "swlio/ipc/messages.h"
#include "swlio/ipc/publisher.h"

namespace swlio::daemon {

/// Voxel rebuilds allowed after the first build before points are thinned instead.
inline constexpr int kMaxVoxelSteps = 4;
/// The time between two publications is at least this many times the last build's.
inline constexpr double kPeriodPerBuild = 20.0;

/// A merged map cloud within the point cap.
struct MapCloud {
  std::vector<Eigen::Vector3f> points_map;  ///< map frame, m
  double voxel_m = 0.0;                     ///< the voxel it was merged with
  size_t keep_every = 1;                    ///< thinning after the last voxel (1: none)
  int builds = 0;                           ///< MergedMapCloud calls it took
};

/// One merge of a map at a voxel size, keeping at most `limit.max_points` centroids and counting
/// all of them: estimator::MergedMapCloud of a SavedMap, or LoopClosure::MergedCloud of the
/// graph's own store (no copy of it).
using MergeFn = std::function<std::optional<std::vector<Eigen::Vector3f>>(
    double voxel_m, const estimator::MergedCloudLimit& limit, std::string* error)>;

/// Merges the map into at most `max_points` points (≥ 1), starting at `start_voxel_m` (the
/// rule above), beating `beat` after each merge. std::nullopt with *error when the merge
/// refuses the map (a non-finite or far point).
std::optional<MapCloud> BuildMapCloud(const MergeFn& merge,
                                      size_t max_points,
                                      double start_voxel_m,
                                      std::string* error,
                                      const Watchdog::Handle& beat = {});
/// The same for a SavedMap.
std::optional<MapCloud> BuildMapCloud(const estimator::SavedMap& map,
                                      size_t max_points,
                                      double start_voxel_m,
                                      std::string* error,
                                      const Watchdog::Handle& beat = {});

/// `points_map` as a height-1 PointCloud2 with x, y, z float32 (point_step 12).
ipc::PointCloud2 ToPointCloud2(const std::vector<Eigen::Vector3f>& points_map,
                               int64_t t_ns,
                               const std::string& frame_id);

struct MapPublishCounters {
  bool enabled = false;
  uint64_t published = 0;    ///< maps written
  uint64_t failures = 0;     ///< maps not written: the merge refused the map or DDS the write
  bool last_failed = false;  ///< the newest attempt was such a failure
  uint64_t points = 0;       ///< last map written
  uint64_t bytes = 0;        ///< its PointCloud2 data
  double voxel_m = 0.0;      ///< its voxel
  double build_ms = 0.0;     ///< wall time to snapshot, merge and pack it
  double write_ms = 0.0;     ///< wall time of its DDS write
};

class MapPublisher {
 public:
  /// `publisher` may be null (tests): maps are built and counted but not written.
  /// `period_s` > 0: the least time between two publications while mapping (longer when the
  /// build takes more than 1 / kPeriodPerBuild of it).
  MapPublisher(ipc::Publisher* publisher, std::string frame_id, size_t max_points, double period_s);

  /// Mapping: the graph grew or was corrected; a new map is due once the period has passed.
  void MarkChanged() { changed_ = true; }
  /// A change is pending and the period since the last publication is over.
  bool Due(int64_t now_ns) const { return changed_ && now_ns >= next_ns_; }

  /// Stamps through `stamps` (not owned, outlives this; its offset sampled by the publisher
  /// thread). Without it the stamps are CLOCK_MONOTONIC. Call before the first Publish.
  void StampWith(const StampClock* stamps) { stamps_ = stamps; }

  /// Builds the cloud of `map` and writes it, stamped with the time at which the build started
  /// (on the poses' clock: StampWith). `snapshot_ms`: what making `map` took (counted
  /// in build_ms). Beats `beat` between the stages. False when nothing was written.
  bool Publish(const estimator::SavedMap& map,
               const Watchdog::Handle& beat,
               double snapshot_ms = 0.0);
  /// The same for a map given by its merge and its node count (for the log).
  bool Publish(const MergeFn& merge,
               size_t nodes,
               const Watchdog::Handle& beat,
               double snapshot_ms = 0.0);

  MapPublishCounters counters() const;

 private:
  ipc::Publisher* publisher_;
  const StampClock* stamps_ = nullptr;
  std::string frame_id_;
  size_t max_points_;
  int64_t period_ns_;
  double voxel_m_;  ///< where the next build starts
  bool changed_ = false;
  int64_t next_ns_ = 0;
  std::atomic<uint64_t> published_{0}, failures_{0}, points_{0}, bytes_{0};
  std::atomic<double> voxel_used_m_{0.0}, build_ms_{0.0}, write_ms_{0.0};
  std::atomic<bool> last_failed_{false};
};

}  // namespace swlio::daemon

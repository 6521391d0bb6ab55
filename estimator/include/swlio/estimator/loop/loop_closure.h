#pragma once
/// @file
/// Loop closure (issue 8; the paper's global correction, §2): keyframes of the odometry become
/// nodes of a pose graph (pose_graph.h) joined by odometry edges. Candidates for the newest
/// node, each at least `min_separation_s` older: the nearest node within `search_radius_m` (in
/// the corrected frame, so a loop is found after moderate drift), and the node with the
/// nearest place descriptor (scan_context.h) within the drift's reach (loop_closure_config.h).
/// One is verified by registration (loop_verifier.h) per attempt, from the graph's relative
/// pose: the radius candidate, or the descriptor's when it points elsewhere (then the two take
/// turns). An accepted loop adds a loop edge and the graph is
/// optimized; the χ² check there switches off loops the rest of the graph contradicts.
/// Memory (issue 33): node clouds are kept in float, and only for nodes that map a new place
/// (keyframe_store.h, LoopClosureConfig::place_radius_m); only those are candidates and go into
/// a saved map. A node on a place already held keeps its pose (graph, trajectory) alone.
///
/// Frames: the odometry's world ("odom", continuous, what the window estimator works in) and
/// the corrected "map". `T_map_odom()` is the correction at the newest node: the pose output is
/// T_map_odom · T_odom_imu, and `CorrectedPose` re-expresses any earlier odometry pose with the
/// correction of the node it follows (for the optimized trajectory after a run).
/// GNSS (optional, `gnss`): fixes become position edges on the nodes (gnss_associator.h);
/// once they span `align_min_distance_m` the map-to-ENU alignment is fitted and added to the
/// graph, which is then optimized every `optimize_every_fixes` new edges. The map frame stays
/// the odometry's at the first node; `T_enu_map()` georeferences it.
/// Pure library (no threads, no clock): the daemon runs it in its own thread.

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/estimator/common/keyframe_cloud.h"
#include "swlio/estimator/gnss/gnss_associator.h"
#include "swlio/estimator/loop/keyframe_store.h"
#include "swlio/estimator/loop/loop_closure_config.h"
#include "swlio/estimator/loop/loop_verifier.h"
#include "swlio/estimator/loop/pose_graph.h"
#include "swlio/estimator/loop/scan_context.h"
#include "swlio/estimator/map/merged_cloud_builder.h"
#include "swlio/estimator/map/saved_map.h"

namespace swlio::estimator {

/// One verification: which nodes, and what it found.
struct LoopAttempt {
  size_t candidate = 0;        ///< older node
  size_t node = 0;             ///< newest node
  double distance_m = 0.0;     ///< between their corrected positions before the check
  bool by_descriptor = false;  ///< found by the place descriptor (else by radius)
  LoopCheck check;
};

struct LoopClosureUpdate {
  bool node_added = false;
  bool attempted = false;
  LoopAttempt attempt;     ///< valid when attempted
  bool optimized = false;  ///< a loop was accepted (or GNSS edges added) and the graph solved
  size_t gnss_edges_added = 0;
  PoseGraphSummary summary;
};

struct LoopClosureStats {
  size_t nodes = 0;
  size_t attempts = 0;
  size_t accepted = 0;
  size_t rejected = 0;
  GnssStats gnss;
  size_t gnss_edges = 0;
  size_t gnss_switched_off = 0;
  size_t gnss_gated = 0;  ///< refused by the innovation gate (gnss_config.h)
  bool gnss_aligned = false;
  /// Stored points the nodes' sweeps saw through and dropped (MapVisibilityConfig).
  size_t dynamic_removed = 0;
};

class LoopClosure {
 public:
  explicit LoopClosure(const LoopClosureConfig& config);

  /// Offers an odometry keyframe (time order); it becomes a node when far enough from the
  /// last one, and then a loop is looked for.
  LoopClosureUpdate AddKeyframe(const KeyframeCloud& keyframe);
  /// Offers a GNSS fix (time order; used with `gnss.enabled`).
  LoopClosureUpdate AddGnss(const GnssFix& fix);
  /// The map frame in the local ENU frame (GNSS), none before the alignment.
  std::optional<Eigen::Isometry3d> T_enu_map() const;
  /// The ENU origin in use (configured, or the first fix), none before.
  std::optional<Geodetic> enu_origin() const;

  /// Re-anchors the map frame (an operator's pose hint while mapping): every node, the
  /// correction and what follows move by `A` (T_map' = A · T_map). False (nothing changed) with
  /// GNSS on: then the map frame is tied to ENU.
  bool Reanchor(const Eigen::Isometry3d& A);
  /// The correction at the newest node (identity before the first loop).
  Eigen::Isometry3d T_map_odom() const;
  /// `T_odom_imu` at `t_ns` in the map frame, with the correction of the last node at or
  /// before `t_ns` (the first node's before it).
  Eigen::Isometry3d CorrectedPose(int64_t t_ns, const Eigen::Isometry3d& T_odom_imu) const;

  const LoopClosureStats& stats() const { return stats_; }
  const std::vector<LoopAttempt>& attempts() const { return attempts_; }
  size_t nodes() const { return nodes_.size(); }
  /// Node i's pose in the map frame (optimized) and in the odometry frame (as received).
  Eigen::Isometry3d T_map_imu(size_t i) const { return graph_.pose(i); }
  /// Node i's time and poses as received (its clouds are in store(), not here).
  const KeyframeCloud& node(size_t i) const { return nodes_[i]; }
  /// The nodes' clouds: which nodes keep one, and their bytes.
  const KeyframeStore& store() const { return store_; }
  /// Every node at its current map pose, oldest first.
  std::vector<MapNode> MapPath() const;
  /// Node i's place descriptor.
  const ScanContext& descriptor(size_t i) const { return descriptors_.at(i); }
  /// The map to save (saved_map.h): every node that keeps a cloud, at its current map pose,
  /// with its features and descriptor.
  SavedMap ToSavedMap() const;
  /// MergedMapCloud(ToSavedMap(), voxel_m, error) (map_pcd.h), the same cloud to the last bit,
  /// without the SavedMap copy of every cloud in double.
  /// `limit` caps the centroids kept (merged_cloud_builder.h).
  std::optional<std::vector<Eigen::Vector3f>> MergedCloud(double voxel_m,
                                                          std::string* error,
                                                          MergedCloudLimit limit = {}) const;
  /// The nodes ToSavedMap would hold (those that keep a cloud).
  size_t map_nodes() const { return store_.clouds(); }

 private:
  bool IsNewNode(const KeyframeCloud& keyframe) const;
  /// Whether an old-enough node that keeps a cloud holds the place of node `newest` already.
  bool IsKnownPlace(size_t newest, int64_t t_ns) const;
  /// The nearest old-enough node within the search radius of the newest; false when none.
  bool FindCandidate(size_t newest, size_t* candidate, double* distance_m) const;
  /// The old-enough node within the drift's reach with the nearest descriptor; false when
  /// none is near enough.
  bool FindDescriptorCandidate(size_t newest, size_t* candidate) const;
  /// Which candidate to verify now (false: none).
  bool ChooseCandidate(size_t newest, LoopAttempt* attempt, Eigen::Isometry3d* guess);
  LoopSubmap BuildSubmap(size_t candidate, int64_t newest_t_ns) const;
  LoopCheck Verify(const LoopAttempt& attempt,
                   const Eigen::Isometry3d& guess,
                   const KeyframeCloud& keyframe) const;
  /// Moving objects out of the stored clouds with the newest node's sweep (MapVisibilityConfig).
  void RemoveSeenThrough(size_t newest, const KeyframeCloud& keyframe);
  /// Loop detection for the newest node (AddKeyframe's second half).
  void DetectLoop(const KeyframeCloud& keyframe, LoopClosureUpdate* update);
  /// Solves the graph and takes its correction at the newest node.
  void OptimizeGraph(LoopClosureUpdate* update);
  /// New GNSS observations into the graph (after the alignment), optimizing when enough.
  void ApplyGnss(LoopClosureUpdate* update);
  /// Fits the map-to-ENU alignment from the waiting observations once they span enough.
  bool TryAlignGnss();
  /// The innovation gate (GnssConfig::gate_sigmas); records the innovation of a fix it takes.
  bool PassesGnssGate(const GnssObservation& o);

  LoopClosureConfig config_;
  PoseGraph graph_;
  std::vector<KeyframeCloud> nodes_;  ///< poses in the odometry frame, without their clouds
  KeyframeStore store_;               ///< the clouds
  ScanContextDatabase descriptors_;   ///< one per node
  std::vector<double> path_m_;        ///< odometry distance driven up to each node
  bool descriptor_turn_ = false;      ///< the descriptor's candidate goes next when both differ
  std::vector<LoopAttempt> attempts_;
  LoopClosureStats stats_;
  size_t since_attempt_ = 0;
  /// The correction of the last optimization, and the nodes that existed then.
  Eigen::Isometry3d T_map_odom_ = Eigen::Isometry3d::Identity();
  size_t optimized_nodes_ = 0;
  std::unique_ptr<GnssAssociator> gnss_;       ///< null unless gnss.enabled
  std::vector<GnssObservation> gnss_waiting_;  ///< before the alignment
  int gnss_since_optimize_ = 0;
  std::deque<double> gnss_innovations_;  ///< of the last accepted fixes, receiver σ units
  int gnss_refused_in_a_row_ = 0;
  /// The last nodes' sweeps (MapVisibilityConfig::recent_nodes), oldest first.
  std::deque<std::shared_ptr<const VisibilityImage>> recent_images_;
};

}  // namespace swlio::estimator

#include "swlio/estimator/loop/loop_closure.h"

#include <algorithm>
#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/estimator/loop/keyframe_descriptor.h"  // KeyframeDescriptor
#include "swlio/estimator/map/merged_cloud_builder.h"

namespace swlio::estimator {
namespace {

/// The keyframe's time and poses (the clouds go to the store).
KeyframeCloud PosesOnly(const KeyframeCloud& keyframe) {
  return {keyframe.t_ns, keyframe.T_world_imu, keyframe.T_imu_lidar, {}, {}, nullptr};
}

}  // namespace

LoopClosure::LoopClosure(const LoopClosureConfig& config)
    : config_(config),
      graph_(config.loop_kernel, config.max_loop_chi2),
      descriptors_(config.descriptor) {
  if (config_.gnss.enabled) {
    gnss_ = std::make_unique<GnssAssociator>(config_.gnss);
    graph_.SetGnssRobustness(config_.gnss.kernel, config_.gnss.max_chi2);
  }
}

bool LoopClosure::IsNewNode(const KeyframeCloud& keyframe) const {
  if (nodes_.empty()) return true;
  const Eigen::Isometry3d delta = nodes_.back().T_world_imu.inverse() * keyframe.T_world_imu;
  return delta.translation().norm() >= config_.keyframe_distance_m ||
         lie::Angle(delta.rotation()) >= config_.keyframe_angle_rad;
}

LoopClosureUpdate LoopClosure::AddKeyframe(const KeyframeCloud& keyframe) {
  LoopClosureUpdate update;
  if (gnss_) gnss_->AddOdometry(keyframe.t_ns, keyframe.T_world_imu);
  if (!IsNewNode(keyframe) || (!nodes_.empty() && keyframe.t_ns <= nodes_.back().t_ns))
    return update;
  const size_t newest = graph_.AddNode(T_map_odom() * keyframe.T_world_imu);
  if (newest > 0) {
    graph_.AddOdometryEdge(
        newest - 1, newest, nodes_.back().T_world_imu.inverse() * keyframe.T_world_imu,
        DiagonalSqrtInformation(config_.odometry_sigma_m, config_.odometry_sigma_rad));
  }
  path_m_.push_back(nodes_.empty() ? 0.0
                                   : path_m_.back() + (keyframe.T_world_imu.translation() -
                                                       nodes_.back().T_world_imu.translation())
                                                          .norm());
  const bool known_place = IsKnownPlace(newest, keyframe.t_ns);
  nodes_.push_back(PosesOnly(keyframe));
  store_.Add(keyframe, !known_place);
  RemoveSeenThrough(newest, keyframe);
  descriptors_.Add(KeyframeDescriptor(config_.descriptor, keyframe));
  update.node_added = true;
  stats_.nodes = nodes_.size();
  if (config_.enabled) DetectLoop(keyframe, &update);
  if (known_place) descriptors_.Release(newest);  // it was only needed for its own search
  if (gnss_ && !update.optimized) {
    ApplyGnss(&update);
    if (gnss_since_optimize_ >= config_.gnss.optimize_every_fixes) OptimizeGraph(&update);
  }
  return update;
}

void LoopClosure::RemoveSeenThrough(size_t newest, const KeyframeCloud& keyframe) {
  const MapVisibilityConfig& c = config_.visibility;
  if (!c.enabled || keyframe.visibility == nullptr) return;
  const VisibilityImage& image = *keyframe.visibility;
  const auto remove_at = static_cast<int>(c.votes_to_remove);
  // The older clouds in the map frame (graph poses), brought into the image's odometry world.
  const Eigen::Isometry3d T_map_lidar = graph_.pose(newest) * keyframe.T_imu_lidar;
  const Eigen::Isometry3d T_world_map = image.T_world_lidar() * T_map_lidar.inverse();
  for (size_t k = 0; k < newest; ++k) {
    if (!store_.has_cloud(k) ||
        (graph_.pose(k).translation() - T_map_lidar.translation()).norm() > c.check_radius_m)
      continue;
    const Eigen::Isometry3d T = T_world_map * graph_.pose(k) * nodes_[k].T_imu_lidar;
    stats_.dynamic_removed += store_.VoteAndRemove(
        k, remove_at, [&](const Eigen::Vector3f& p) { return image.Test(T * p.cast<double>()); });
  }
  // The new cloud against the sweeps just before it (all in the odometry world, moments apart).
  if (store_.has_cloud(newest)) {
    const Eigen::Isometry3d T = keyframe.T_world_imu * keyframe.T_imu_lidar;
    for (const std::shared_ptr<const VisibilityImage>& earlier : recent_images_) {
      stats_.dynamic_removed += store_.VoteAndRemove(
          newest, remove_at,
          [&](const Eigen::Vector3f& p) { return earlier->Test(T * p.cast<double>()); });
    }
  }
  recent_images_.push_back(keyframe.visibility);
  while (recent_images_.size() > static_cast<size_t>(c.recent_nodes)) recent_images_.pop_front();
}

bool LoopClosure::IsKnownPlace(size_t newest, int64_t t_ns) const {
  if (config_.place_radius_m <= 0.0) return false;
  const auto min_gap_ns = static_cast<int64_t>(config_.min_separation_s * 1e9);
  const Eigen::Isometry3d& T_map_newest = graph_.pose(newest);
  for (size_t k = 0; k < newest && t_ns - nodes_[k].t_ns >= min_gap_ns; ++k) {
    if (!store_.has_cloud(k)) continue;
    const Eigen::Isometry3d delta = graph_.pose(k).inverse() * T_map_newest;
    if (delta.translation().norm() <= config_.place_radius_m &&
        lie::Angle(delta.rotation()) <= config_.place_angle_rad)
      return true;
  }
  return false;
}

void LoopClosure::DetectLoop(const KeyframeCloud& keyframe, LoopClosureUpdate* out) {
  LoopClosureUpdate& update = *out;
  const size_t newest = nodes_.size() - 1;
  if (++since_attempt_ < static_cast<size_t>(config_.attempt_every_nodes)) return;

  Eigen::Isometry3d guess;
  if (!ChooseCandidate(newest, &update.attempt, &guess)) return;
  const size_t candidate = update.attempt.candidate;
  since_attempt_ = 0;
  update.attempted = true;
  update.attempt.check = Verify(update.attempt, guess, keyframe);
  attempts_.push_back(update.attempt);
  ++stats_.attempts;
  if (update.attempt.check.verdict != LoopVerdict::kAccepted) {
    ++stats_.rejected;
    return;
  }
  ++stats_.accepted;
  const Eigen::Isometry3d T_candidate_imu =
      update.attempt.check.T_candidate_lidar * keyframe.T_imu_lidar.inverse();
  graph_.AddLoopEdge(candidate, newest, T_candidate_imu,
                     DiagonalSqrtInformation(config_.loop_sigma_m, config_.loop_sigma_rad));
  if (gnss_) ApplyGnss(&update);  // the new edges join this solve
  OptimizeGraph(&update);
}

void LoopClosure::OptimizeGraph(LoopClosureUpdate* update) {
  update->summary = graph_.Optimize(config_.max_iterations);
  update->optimized = update->summary.solved;
  if (update->optimized) {
    optimized_nodes_ = nodes_.size();
    T_map_odom_ = graph_.pose(nodes_.size() - 1) * nodes_.back().T_world_imu.inverse();
    gnss_since_optimize_ = 0;
  }
  stats_.gnss_switched_off = graph_.gnss_switched_off();
}

Eigen::Isometry3d LoopClosure::T_map_odom() const { return T_map_odom_; }

bool LoopClosure::Reanchor(const Eigen::Isometry3d& A) {
  if (gnss_) return false;
  graph_.TransformAll(A);
  T_map_odom_ = A * T_map_odom_;
  return true;
}

LoopClosureUpdate LoopClosure::AddGnss(const GnssFix& fix) {
  LoopClosureUpdate update;
  if (!gnss_) return update;
  gnss_->AddFix(fix);
  ApplyGnss(&update);
  if (gnss_since_optimize_ >= config_.gnss.optimize_every_fixes) OptimizeGraph(&update);
  return update;
}

void LoopClosure::ApplyGnss(LoopClosureUpdate* update) {
  for (const GnssObservation& o : gnss_->Take(nodes_)) gnss_waiting_.push_back(o);
  stats_.gnss = gnss_->stats();
  if (!graph_.has_enu_alignment() && !TryAlignGnss()) return;
  for (const GnssObservation& o : gnss_waiting_) {
    if (!PassesGnssGate(o)) continue;
    if (graph_.AddGnssEdge(o.node, o.antenna_imu_m, o.fix_enu_m, o.sigma_h_m, o.sigma_v_m)) {
      ++update->gnss_edges_added;
      ++gnss_since_optimize_;
    }
  }
  gnss_waiting_.clear();
  stats_.gnss_edges = graph_.gnss_edges();
  stats_.gnss_aligned = true;
}

bool LoopClosure::PassesGnssGate(const GnssObservation& o) {
  // Where the graph has the antenna now (a node newer than the last solve sits at the current
  // correction times its odometry, as the graph's initial value does).
  const Eigen::Vector3d predicted = graph_.T_enu_map() * (graph_.pose(o.node) * o.antenna_imu_m);
  const Eigen::Vector3d d = o.fix_enu_m - predicted;
  const double sh = o.sigma_h_m / o.inflation, sv = o.sigma_v_m / o.inflation;
  const double distance =
      std::sqrt(d.head<2>().squaredNorm() / (sh * sh) + d.z() * d.z() / (sv * sv));
  std::vector<double> recent(gnss_innovations_.begin(), gnss_innovations_.end());
  double median = 1.0;
  if (!recent.empty()) {
    std::nth_element(recent.begin(), recent.begin() + static_cast<long>(recent.size() / 2),
                     recent.end());
    median = std::max(1.0, recent[recent.size() / 2]);
  }
  const bool pass = distance <= config_.gnss.gate_sigmas * median ||
                    gnss_refused_in_a_row_ >= config_.gnss.gate_reset_after;
  if (!pass) {
    ++gnss_refused_in_a_row_;
    ++stats_.gnss_gated;
    return false;
  }
  gnss_refused_in_a_row_ = 0;
  gnss_innovations_.push_back(distance);
  if (gnss_innovations_.size() > 30) gnss_innovations_.pop_front();
  return true;
}

bool LoopClosure::TryAlignGnss() {
  if (gnss_waiting_.size() < 3) return false;
  std::vector<Eigen::Vector3d> map_m, enu_m;
  double span_m = 0.0;
  for (const GnssObservation& o : gnss_waiting_) {
    map_m.push_back(graph_.pose(o.node) * o.antenna_imu_m);
    enu_m.push_back(o.fix_enu_m);
    span_m = std::max(span_m, (enu_m.back() - enu_m.front()).head<2>().norm());
  }
  if (span_m < config_.gnss.align_min_distance_m) return false;
  graph_.SetEnuAlignment(FitEnuAlignment(map_m, enu_m));
  return true;
}

std::optional<Eigen::Isometry3d> LoopClosure::T_enu_map() const {
  if (!graph_.has_enu_alignment()) return std::nullopt;
  return graph_.T_enu_map();
}

std::optional<Geodetic> LoopClosure::enu_origin() const {
  if (!gnss_) return std::nullopt;
  return gnss_->origin();
}

Eigen::Isometry3d LoopClosure::CorrectedPose(int64_t t_ns,
                                             const Eigen::Isometry3d& T_odom_imu) const {
  if (nodes_.empty()) return T_odom_imu;
  const auto after = std::upper_bound(nodes_.begin(), nodes_.end(), t_ns,
                                      [](int64_t t, const KeyframeCloud& n) { return t < n.t_ns; });
  const size_t k = after == nodes_.begin() ? 0 : static_cast<size_t>(after - nodes_.begin()) - 1;
  // Nodes added since the last optimization sit at T_map_odom_ · odometry (exactly, not
  // through the graph's quaternion round trip).
  if (k >= optimized_nodes_) return T_map_odom_ * T_odom_imu;
  return graph_.pose(k) * nodes_[k].T_world_imu.inverse() * T_odom_imu;
}

std::vector<MapNode> LoopClosure::MapPath() const {
  std::vector<MapNode> out;
  out.reserve(nodes_.size());
  for (size_t i = 0; i < nodes_.size(); ++i)
    out.push_back({nodes_[i].t_ns, CorrectedPose(nodes_[i].t_ns, nodes_[i].T_world_imu)});
  return out;
}

SavedMap LoopClosure::ToSavedMap() const {
  SavedMap map;
  map.descriptor_rings = config_.descriptor.rings;
  map.descriptor_sectors = config_.descriptor.sectors;
  map.descriptor_max_range_m = config_.descriptor.max_range_m;
  map.descriptor_min_range_m = config_.descriptor.min_range_m;
  map.descriptor_height_offset_m = config_.descriptor.height_offset_m;
  map.nodes.reserve(store_.clouds());
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  for (size_t i = 0; i < nodes_.size(); ++i) {
    if (!store_.has_cloud(i)) continue;
    const KeyframeCloud& n = nodes_[i];
    map.nodes.push_back({n.t_ns, CorrectedPose(n.t_ns, n.T_world_imu), n.T_imu_lidar,
                         store_.Planes(i, I), store_.Edges(i, I), descriptors_.at(i).cells});
  }
  return map;
}

std::optional<std::vector<Eigen::Vector3f>> LoopClosure::MergedCloud(double voxel_m,
                                                                     std::string* error,
                                                                     MergedCloudLimit limit) const {
  MergedCloudBuilder builder(voxel_m, MergedCloudBuilder::kMaxRecords, limit);
  while (builder.NextPass()) {
    for (size_t i = 0; i < nodes_.size(); ++i) {
      if (!store_.has_cloud(i)) continue;
      const KeyframeCloud& n = nodes_[i];
      store_.Visit(i, [&](const std::vector<Eigen::Vector3f>& planes_lidar,
                          const std::vector<Eigen::Vector3f>& edges_lidar) {
        builder.AddNode(CorrectedPose(n.t_ns, n.T_world_imu) * n.T_imu_lidar, planes_lidar,
                        edges_lidar);
      });
    }
  }
  return builder.Finish(error);
}

bool LoopClosure::ChooseCandidate(size_t newest, LoopAttempt* attempt, Eigen::Isometry3d* guess) {
  size_t by_radius = 0, by_descriptor = 0;
  double distance_m = 0.0;
  const bool radius = FindCandidate(newest, &by_radius, &distance_m);
  const bool descriptor =
      config_.descriptor_candidates && FindDescriptorCandidate(newest, &by_descriptor);
  // The descriptor's candidate counts as the same place when it lies in the radius
  // candidate's submap.
  const auto h = static_cast<size_t>(config_.submap_half_width);
  const bool same =
      radius && descriptor && by_descriptor + h >= by_radius && by_descriptor <= by_radius + h;
  if (!radius && !descriptor) return false;
  const bool use_descriptor = descriptor && (!radius || (!same && descriptor_turn_));
  if (radius && descriptor && !same) descriptor_turn_ = !descriptor_turn_;
  attempt->node = newest;
  attempt->by_descriptor = use_descriptor;
  attempt->candidate = use_descriptor ? by_descriptor : by_radius;
  attempt->distance_m =
      (graph_.pose(attempt->candidate).translation() - graph_.pose(newest).translation()).norm();
  *guess =
      graph_.pose(attempt->candidate).inverse() * graph_.pose(newest) * nodes_[newest].T_imu_lidar;
  return true;
}

bool LoopClosure::FindDescriptorCandidate(size_t newest, size_t* candidate) const {
  const auto min_gap_ns = static_cast<int64_t>(config_.min_separation_s * 1e9);
  const int64_t t_ns = nodes_[newest].t_ns;
  const Eigen::Vector3d p = graph_.pose(newest).translation();
  const auto matches = descriptors_.Query(descriptors_.at(newest), 1, [&](size_t k) {
    const double reach_m =
        config_.search_radius_m + config_.max_drift_ratio * (path_m_[newest] - path_m_[k]);
    return k < newest && t_ns - nodes_[k].t_ns >= min_gap_ns &&
           (graph_.pose(k).translation() - p).norm() <= reach_m;
  });
  if (matches.empty()) return false;
  *candidate = matches.front().first;
  return true;
}

bool LoopClosure::FindCandidate(size_t newest, size_t* candidate, double* distance_m) const {
  const Eigen::Vector3d p = graph_.pose(newest).translation();
  const auto min_gap_ns = static_cast<int64_t>(config_.min_separation_s * 1e9);
  double best = config_.search_radius_m;
  bool found = false;
  for (size_t k = 0; k < newest && nodes_[newest].t_ns - nodes_[k].t_ns >= min_gap_ns; ++k) {
    if (!store_.has_cloud(k)) continue;  // no submap to verify against
    const double d = (graph_.pose(k).translation() - p).norm();
    if (d < best) {
      best = d;
      *candidate = k;
      found = true;
    }
  }
  *distance_m = best;
  return found;
}

LoopSubmap LoopClosure::BuildSubmap(size_t candidate, int64_t newest_t_ns) const {
  LoopSubmap submap(config_.submap);
  const Eigen::Isometry3d T_candidate_map = graph_.pose(candidate).inverse();
  const auto min_gap_ns = static_cast<int64_t>(config_.min_separation_s * 1e9);
  const size_t h = static_cast<size_t>(config_.submap_half_width);
  const size_t first = candidate > h ? candidate - h : 0;
  const size_t last = std::min(nodes_.size() - 1, candidate + h);
  for (size_t m = first; m <= last; ++m) {
    if (newest_t_ns - nodes_[m].t_ns < min_gap_ns || !store_.has_cloud(m)) continue;
    const Eigen::Isometry3d T = T_candidate_map * graph_.pose(m) * nodes_[m].T_imu_lidar;
    submap.planes.Insert(store_.Planes(m, T));
    submap.edges.Insert(store_.Edges(m, T));
  }
  return submap;
}

LoopCheck LoopClosure::Verify(const LoopAttempt& attempt,
                              const Eigen::Isometry3d& guess,
                              const KeyframeCloud& keyframe) const {
  // The newest node's own cloud as received (double), not the store's.
  return VerifyLoop(config_, keyframe.planes_lidar, keyframe.edges_lidar,
                    BuildSubmap(attempt.candidate, keyframe.t_ns), guess);
}

}  // namespace swlio::estimator

#include "swlio/estimator/map/map_localizer.h"

#include <algorithm>
#include <utility>

#include "swlio/core/lie.h"
#include "swlio/estimator/loop/keyframe_descriptor.h"

namespace swlio::estimator {
namespace {

/// The odometry moved at least `m` or turned at least `rad` from `from` to `to`.
bool Moved(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to, double m, double rad) {
  const Eigen::Isometry3d d = from.inverse() * to;
  return d.translation().norm() >= m || lie::Angle(d.linear()) >= rad;
}

/// How the map's descriptors were made; every one is compared in full.
ScanContextConfig DescriptorConfigOf(const SavedMap& map, const LocalizationConfig& config) {
  ScanContextConfig c;
  c.candidates = static_cast<int>(std::max<size_t>(map.nodes.size(), 1));
  c.max_distance = config.relocalize_max_descriptor_distance;
  c.rings = map.descriptor_rings;
  c.sectors = map.descriptor_sectors;
  c.max_range_m = map.descriptor_max_range_m;
  c.min_range_m = map.descriptor_min_range_m;
  c.height_offset_m = map.descriptor_height_offset_m;
  return c;
}

}  // namespace

const char* ToString(LocalizationState state) {
  switch (state) {
    case LocalizationState::kRelocalizing:
      return "relocalizing";
    case LocalizationState::kConfirming:
      return "confirming";
    case LocalizationState::kTracking:
      return "tracking";
  }
  return "?";
}

MapLocalizer::MapLocalizer(SavedMap map, const LocalizationConfig& config)
    : map_(std::move(map)),
      config_(config),
      descriptor_config_(DescriptorConfigOf(map_, config)),
      descriptors_(descriptor_config_) {
  for (const SavedMapNode& n : map_.nodes) {
    descriptors_.Add(
        ScanContextFromCells(map_.descriptor_rings, map_.descriptor_sectors, n.descriptor));
  }
}

LocalizationUpdate MapLocalizer::AddKeyframe(const KeyframeCloud& keyframe) {
  ++stats_.keyframes;
  LocalizationUpdate u;
  if (state_ == LocalizationState::kRelocalizing) {
    if (DueForRelocalization(keyframe)) {
      u = Relocalize(keyframe);
    } else {
      ++stats_.relocalization_deferred;
    }
  } else if (state_ == LocalizationState::kConfirming || DueForTracking(keyframe)) {
    u = Track(keyframe);
  }
  u.state = state_;
  return u;
}

bool MapLocalizer::DueForTracking(const KeyframeCloud& keyframe) const {
  return Moved(T_odom_imu_last_registered_, keyframe.T_world_imu, config_.track_every_m,
               config_.track_every_rad);
}

bool MapLocalizer::DueForRelocalization(const KeyframeCloud& keyframe) const {
  return !T_odom_imu_last_try_ || Moved(*T_odom_imu_last_try_, keyframe.T_world_imu,
                                        config_.relocalize_every_m, config_.relocalize_every_rad);
}

void MapLocalizer::StartRelocalizing() {
  state_ = LocalizationState::kRelocalizing;
  T_odom_imu_last_try_.reset();
}

LocalizationUpdate MapLocalizer::Relocalize(const KeyframeCloud& keyframe) {
  LocalizationUpdate u;
  if (map_.nodes.empty()) return u;
  ++stats_.relocalization_tries;
  T_odom_imu_last_try_ = keyframe.T_world_imu;
  const ScanContext query = KeyframeDescriptor(descriptor_config_, keyframe);
  const auto matches = DistinctPlaces(descriptors_.Query(query, map_.nodes.size(), {}));
  const Eigen::Isometry3d T_Gq_imu = T_gravity_imu(keyframe.T_world_imu, keyframe.T_imu_lidar);
  struct Hypothesis {
    size_t node;
    LoopCheck check;
    Eigen::Vector3d p_map;
  };
  std::vector<Hypothesis> accepted;
  for (const auto& [node, match] : matches) {
    const SavedMapNode& n = map_.nodes[node];
    const Eigen::Isometry3d guess = T_candidate_lidar_from_descriptor(
        T_gravity_imu(n.T_map_imu, n.T_imu_lidar), match.yaw_rad, T_Gq_imu, keyframe.T_imu_lidar);
    const LoopCheck check = Register(keyframe, node, guess, true);
    ++u.registrations;
    ++stats_.relocalization_registrations;
    u.check = check;
    u.map_node = node;
    if (check.verdict == LoopVerdict::kAccepted)
      accepted.push_back({node, check, (n.T_map_imu * check.T_candidate_lidar).translation()});
  }
  if (accepted.empty()) return u;
  const auto best = std::max_element(
      accepted.begin(), accepted.end(),
      [](const Hypothesis& a, const Hypothesis& b) { return a.check.fitness < b.check.fitness; });
  for (const Hypothesis& h : accepted) {
    if ((h.p_map - best->p_map).norm() > config_.distinct_m &&
        best->check.fitness - h.check.fitness < config_.relocalize_min_margin) {
      ++stats_.ambiguous;
      return u;  // two places fit about as well: wait for a keyframe that tells them apart
    }
  }
  u.accepted = true;
  u.check = best->check;
  u.map_node = best->node;
  ++stats_.hypotheses;
  Accept(keyframe, u.map_node, u.check);
  confirmed_ = 0;
  state_ =
      config_.confirmations > 0 ? LocalizationState::kConfirming : LocalizationState::kTracking;
  if (localized() && stats_.first_localized_t_ns < 0) stats_.first_localized_t_ns = keyframe.t_ns;
  return u;
}

std::vector<std::pair<size_t, ScanContextMatch>> MapLocalizer::DistinctPlaces(
    const std::vector<std::pair<size_t, ScanContextMatch>>& matches) const {
  std::vector<std::pair<size_t, ScanContextMatch>> out;
  for (const auto& m : matches) {
    if (out.size() >= static_cast<size_t>(config_.relocalize_candidates)) break;
    const Eigen::Vector3d p = map_.nodes[m.first].T_map_imu.translation();
    const bool near_kept = std::any_of(out.begin(), out.end(), [&](const auto& k) {
      return (map_.nodes[k.first].T_map_imu.translation() - p).norm() < 2.0 * config_.distinct_m;
    });
    if (!near_kept) out.push_back(m);
  }
  return out;
}

LocalizationUpdate MapLocalizer::Track(const KeyframeCloud& keyframe) {
  LocalizationUpdate u;
  const Eigen::Isometry3d T_map_imu = T_map_odom_ * keyframe.T_world_imu;
  const std::vector<size_t> near = NodesNear(T_map_imu.translation());
  if (!near.empty()) {
    u.map_node = near.front();
    const Eigen::Isometry3d guess =
        map_.nodes[u.map_node].T_map_imu.inverse() * T_map_imu * keyframe.T_imu_lidar;
    u.check = Register(keyframe, u.map_node, guess, false);
    u.registrations = 1;
    u.accepted = u.check.verdict == LoopVerdict::kAccepted;
  }
  if (u.accepted) {
    ++stats_.tracked;
    failures_ = 0;
    Accept(keyframe, u.map_node, u.check);
    if (state_ == LocalizationState::kConfirming && ++confirmed_ >= config_.confirmations) {
      state_ = LocalizationState::kTracking;
      if (stats_.first_localized_t_ns < 0) stats_.first_localized_t_ns = keyframe.t_ns;
    }
    return u;
  }
  ++stats_.track_failures;
  T_odom_imu_last_registered_ = keyframe.T_world_imu;
  if (state_ == LocalizationState::kConfirming) {
    ++stats_.hypotheses_dropped;
    StartRelocalizing();
    T_map_odom_ = Eigen::Isometry3d::Identity();
  } else if (++failures_ >= config_.lost_after_failures) {
    ++stats_.lost;
    failures_ = 0;
    StartRelocalizing();
  }
  return u;
}

void MapLocalizer::Accept(const KeyframeCloud& keyframe, size_t node, const LoopCheck& check) {
  const Eigen::Isometry3d T_map_imu =
      map_.nodes[node].T_map_imu * check.T_candidate_lidar * keyframe.T_imu_lidar.inverse();
  T_map_odom_ = T_map_imu * keyframe.T_world_imu.inverse();
  T_odom_imu_last_registered_ = keyframe.T_world_imu;
}

std::vector<size_t> MapLocalizer::NodesNear(const Eigen::Vector3d& p_map) const {
  std::vector<std::pair<double, size_t>> near;
  for (size_t i = 0; i < map_.nodes.size(); ++i) {
    const double d = (map_.nodes[i].T_map_imu.translation() - p_map).norm();
    if (d <= config_.submap_radius_m) near.emplace_back(d, i);
  }
  const size_t n = std::min(near.size(), static_cast<size_t>(config_.submap_max_nodes));
  std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(n), near.end());
  std::vector<size_t> out;
  for (size_t k = 0; k < n; ++k) out.push_back(near[k].second);
  return out;
}

LoopSubmap MapLocalizer::BuildSubmap(size_t center, const std::vector<size_t>& nodes) const {
  LoopSubmap submap(config_.registration.submap);
  const Eigen::Isometry3d T_center_map = map_.nodes[center].T_map_imu.inverse();
  std::vector<Eigen::Vector3d> points;
  for (const size_t m : nodes) {
    const SavedMapNode& n = map_.nodes[m];
    const Eigen::Isometry3d T = T_center_map * n.T_map_imu * n.T_imu_lidar;
    points.clear();
    for (const Eigen::Vector3d& p : n.planes_lidar) points.push_back(T * p);
    submap.planes.Insert(points);
    points.clear();
    for (const Eigen::Vector3d& p : n.edges_lidar) points.push_back(T * p);
    submap.edges.Insert(points);
  }
  return submap;
}

LoopCheck MapLocalizer::Register(const KeyframeCloud& keyframe,
                                 size_t center,
                                 const Eigen::Isometry3d& T_center_lidar_guess,
                                 bool relocalizing) const {
  LoopClosureConfig c = config_.registration;
  if (relocalizing) {
    c.max_correction_m = config_.relocalize_max_correction_m;
    c.max_correction_rad = config_.relocalize_max_correction_rad;
  } else {
    c.min_fitness = config_.track_min_fitness;
    c.max_correction_m = config_.track_max_correction_m;
    c.max_correction_rad = config_.track_max_correction_rad;
  }
  std::vector<size_t> nodes = NodesNear(map_.nodes[center].T_map_imu.translation());
  if (nodes.empty()) nodes.push_back(center);
  return VerifyLoop(c, keyframe.planes_lidar, keyframe.edges_lidar, BuildSubmap(center, nodes),
                    T_center_lidar_guess);
}

}  // namespace swlio::estimator

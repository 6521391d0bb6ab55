#include "swlio/estimator/loop_closure.h"

#include <algorithm>

namespace swlio::estimator {
namespace {

double Angle(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

std::vector<Eigen::Vector3d> Transformed(const Eigen::Isometry3d& T,
                                         const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back(T * p);
  return out;
}

}  // namespace

LoopClosure::LoopClosure(const LoopClosureConfig& config)
    : config_(config), graph_(config.loop_kernel, config.max_loop_chi2) {}

bool LoopClosure::IsNewNode(const KeyframeCloud& keyframe) const {
  if (nodes_.empty()) return true;
  const Eigen::Isometry3d delta = nodes_.back().T_world_imu.inverse() * keyframe.T_world_imu;
  return delta.translation().norm() >= config_.keyframe_distance_m ||
         Angle(delta.rotation()) >= config_.keyframe_angle_rad;
}

LoopClosureUpdate LoopClosure::AddKeyframe(const KeyframeCloud& keyframe) {
  LoopClosureUpdate update;
  if (!IsNewNode(keyframe) || (!nodes_.empty() && keyframe.t_ns <= nodes_.back().t_ns))
    return update;
  const size_t newest = graph_.AddNode(T_map_odom() * keyframe.T_world_imu);
  if (newest > 0) {
    graph_.AddOdometryEdge(
        newest - 1, newest, nodes_.back().T_world_imu.inverse() * keyframe.T_world_imu,
        DiagonalSqrtInformation(config_.odometry_sigma_m, config_.odometry_sigma_rad));
  }
  nodes_.push_back(keyframe);
  update.node_added = true;
  stats_.nodes = nodes_.size();
  if (++since_attempt_ < static_cast<size_t>(config_.attempt_every_nodes)) return update;

  size_t candidate = 0;
  double distance_m = 0.0;
  if (!FindCandidate(newest, &candidate, &distance_m)) return update;
  since_attempt_ = 0;
  update.attempted = true;
  update.attempt = Verify(candidate, newest, distance_m);
  attempts_.push_back(update.attempt);
  ++stats_.attempts;
  if (update.attempt.check.verdict != LoopVerdict::kAccepted) {
    ++stats_.rejected;
    return update;
  }
  ++stats_.accepted;
  const Eigen::Isometry3d T_candidate_imu =
      update.attempt.check.T_candidate_lidar * keyframe.T_imu_lidar.inverse();
  graph_.AddLoopEdge(candidate, newest, T_candidate_imu,
                     DiagonalSqrtInformation(config_.loop_sigma_m, config_.loop_sigma_rad));
  update.summary = graph_.Optimize(config_.max_iterations);
  update.optimized = update.summary.solved;
  if (update.optimized) {
    optimized_nodes_ = nodes_.size();
    T_map_odom_ = graph_.pose(newest) * keyframe.T_world_imu.inverse();
  }
  return update;
}

Eigen::Isometry3d LoopClosure::T_map_odom() const { return T_map_odom_; }

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

bool LoopClosure::FindCandidate(size_t newest, size_t* candidate, double* distance_m) const {
  const Eigen::Vector3d p = graph_.pose(newest).translation();
  const auto min_gap_ns = static_cast<int64_t>(config_.min_separation_s * 1e9);
  double best = config_.search_radius_m;
  bool found = false;
  for (size_t k = 0; k < newest && nodes_[newest].t_ns - nodes_[k].t_ns >= min_gap_ns; ++k) {
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
    if (newest_t_ns - nodes_[m].t_ns < min_gap_ns) continue;
    const Eigen::Isometry3d T = T_candidate_map * graph_.pose(m) * nodes_[m].T_imu_lidar;
    submap.planes.Insert(Transformed(T, nodes_[m].planes_lidar));
    submap.edges.Insert(Transformed(T, nodes_[m].edges_lidar));
  }
  return submap;
}

LoopAttempt LoopClosure::Verify(size_t candidate, size_t newest, double distance_m) const {
  LoopAttempt a;
  a.candidate = candidate;
  a.node = newest;
  a.distance_m = distance_m;
  const KeyframeCloud& kf = nodes_[newest];
  const Eigen::Isometry3d guess =
      graph_.pose(candidate).inverse() * graph_.pose(newest) * kf.T_imu_lidar;
  a.check =
      VerifyLoop(config_, kf.planes_lidar, kf.edges_lidar, BuildSubmap(candidate, kf.t_ns), guess);
  return a;
}

}  // namespace swlio::estimator

// MapLocalizer's operator hints (map_localizer.h, "A hint"): relocalization seeded by where a
// person says the robot is, refused with a reason when the scan disagrees.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "swlio/estimator/loop/keyframe_descriptor.h"
#include "swlio/estimator/map/map_localizer.h"

namespace swlio::estimator {
namespace {

/// Fits are sought within this many σ of the hint.
constexpr double kHintSigmas = 3.0;
/// However small the σ, registration may move the hint this much (a click in rviz2 is not
/// more precise than a few decimetres and degrees).
constexpr double kMinSearchM = 0.5;
constexpr double kMinSearchRad = 0.1;

double WrapPi(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

double Azimuth(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

}  // namespace

const char* ToString(HintVerdict verdict) {
  switch (verdict) {
    case HintVerdict::kTracking:
      return "tracking";
    case HintVerdict::kConfirming:
      return "confirming";
    case HintVerdict::kNoMap:
      return "no-map";
    case HintVerdict::kNoFit:
      return "no-fit";
    case HintVerdict::kElsewhere:
      return "elsewhere";
    case HintVerdict::kNoKeyframe:
      return "no-keyframe";
  }
  return "?";
}

HintOutcome MapLocalizer::ApplyHint(const KeyframeCloud& keyframe, const LocalizationHint& hint) {
  ++stats_.hints;
  // The keyframe's best matching places, once: starts near the hint and the global search.
  const auto matches = DistinctPlaces(
      descriptors_.Query(KeyframeDescriptor(descriptor_config_, keyframe), map_.nodes.size(), {}));
  HintOutcome out = FitNearHint(keyframe, hint, matches);
  if (out.verdict == HintVerdict::kNoMap || out.verdict == HintVerdict::kNoFit) {
    ++stats_.hints_refused;
    return out;
  }
  // The global search: a place outside the hint's region that fits clearly better means the
  // hint is wrong; one about as good (a look-alike bay) leaves it to the next keyframes.
  const double region_m = kHintSigmas * std::max(hint.sigma_xy_m, kMinSearchM);
  const Eigen::Isometry3d T_Gq_imu = T_gravity_imu(keyframe.T_world_imu, keyframe.T_imu_lidar);
  bool look_alike = false;
  for (const auto& [node, match] : matches) {
    const SavedMapNode& n = map_.nodes[node];
    if ((n.T_map_imu.translation().head<2>() - out.p_map.head<2>()).norm() <= region_m) continue;
    const Eigen::Isometry3d guess = T_candidate_lidar_from_descriptor(
        T_gravity_imu(n.T_map_imu, n.T_imu_lidar), match.yaw_rad, T_Gq_imu, keyframe.T_imu_lidar);
    const LoopCheck check = Register(keyframe, node, guess, true);
    ++out.registrations;
    if (check.verdict != LoopVerdict::kAccepted) continue;
    const Eigen::Vector3d p =
        (n.T_map_imu * check.T_candidate_lidar * keyframe.T_imu_lidar.inverse()).translation();
    if ((p.head<2>() - out.p_map.head<2>()).norm() <= region_m) continue;  // the same place
    if (check.fitness > out.check.fitness + config_.relocalize_min_margin) {
      out.verdict = HintVerdict::kElsewhere;
      out.p_elsewhere = p;
      out.fitness_elsewhere = check.fitness;
      ++stats_.hints_refused;
      return out;
    }
    if (out.check.fitness - check.fitness < config_.relocalize_min_margin) look_alike = true;
  }
  ++stats_.hypotheses;
  Accept(keyframe, out.map_node, out.check);
  T_odom_imu_last_try_ = keyframe.T_world_imu;
  failures_ = 0;
  confirmed_ = 0;
  if (look_alike && config_.confirmations > 0) {
    out.verdict = HintVerdict::kConfirming;
    state_ = LocalizationState::kConfirming;
  } else {
    out.verdict = HintVerdict::kTracking;
    state_ = LocalizationState::kTracking;
    if (stats_.first_localized_t_ns < 0) stats_.first_localized_t_ns = keyframe.t_ns;
  }
  return out;
}

HintOutcome MapLocalizer::FitNearHint(
    const KeyframeCloud& keyframe,
    const LocalizationHint& hint,
    const std::vector<std::pair<size_t, ScanContextMatch>>& matches) {
  HintOutcome out;
  const double search_m = kHintSigmas * std::max(hint.sigma_xy_m, kMinSearchM);
  const double search_rad = kHintSigmas * std::max(hint.sigma_yaw_rad, kMinSearchRad);
  const Eigen::Vector2d xy(hint.x_m, hint.y_m);
  // The node nearest to the hint (in the plane) gives the height and the submap's centre.
  size_t nearest = 0;
  double nearest_m = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < map_.nodes.size(); ++i) {
    const double d = (map_.nodes[i].T_map_imu.translation().head<2>() - xy).norm();
    if (d < nearest_m) nearest_m = d, nearest = i;
  }
  out.nearest_node_m = nearest_m;
  if (!(nearest_m <= config_.submap_radius_m)) {
    out.verdict = HintVerdict::kNoMap;
    return out;
  }
  Eigen::Isometry3d T_map_imu_hint = Eigen::Isometry3d::Identity();
  T_map_imu_hint.linear() = Eigen::AngleAxisd(hint.yaw_rad, Eigen::Vector3d::UnitZ()) *
                            GravityAlignedFromBody(keyframe.T_world_imu.linear());
  T_map_imu_hint.translation() << hint.x_m, hint.y_m,
      map_.nodes[nearest].T_map_imu.translation().z();

  // Candidates: the hinted pose itself, then descriptor matches of nodes within the region
  // (their yaw and offset from the match), each registered with the region as its bound.
  struct Start {
    size_t node;
    Eigen::Isometry3d T_map_imu;
  };
  std::vector<Start> starts{{nearest, T_map_imu_hint}};
  const Eigen::Isometry3d T_Gq_imu = T_gravity_imu(keyframe.T_world_imu, keyframe.T_imu_lidar);
  for (const auto& [node, match] : matches) {
    const SavedMapNode& n = map_.nodes[node];
    if ((n.T_map_imu.translation().head<2>() - xy).norm() > search_m + config_.distinct_m) continue;
    const Eigen::Isometry3d T_node_lidar = T_candidate_lidar_from_descriptor(
        T_gravity_imu(n.T_map_imu, n.T_imu_lidar), match.yaw_rad, T_Gq_imu, keyframe.T_imu_lidar);
    starts.push_back({node, n.T_map_imu * T_node_lidar * keyframe.T_imu_lidar.inverse()});
  }
  bool any = false;  // an accepted fit within the region (else out holds the best failure)
  for (const Start& s : starts) {
    const LoopCheck check = RegisterFrom(keyframe, s.node, s.T_map_imu, search_m, search_rad);
    ++out.registrations;
    const Eigen::Isometry3d T_map_imu =
        map_.nodes[s.node].T_map_imu * check.T_candidate_lidar * keyframe.T_imu_lidar.inverse();
    const bool fits = check.verdict == LoopVerdict::kAccepted &&
                      (T_map_imu.translation().head<2>() - xy).norm() <= search_m &&
                      std::abs(WrapPi(Azimuth(T_map_imu.linear()) - hint.yaw_rad)) <= search_rad;
    const bool first = out.registrations == 1;
    if (fits ? (!any || check.fitness > out.check.fitness)
             : (!any && (first || check.fitness > out.check.fitness))) {
      any = any || fits;
      out.check = check;
      out.map_node = s.node;
      out.p_map = T_map_imu.translation();
      out.yaw_map_rad = Azimuth(T_map_imu.linear());
    }
  }
  out.verdict = any ? HintVerdict::kTracking : HintVerdict::kNoFit;
  return out;
}

LoopCheck MapLocalizer::RegisterFrom(const KeyframeCloud& keyframe,
                                     size_t node,
                                     const Eigen::Isometry3d& T_map_imu_guess,
                                     double max_m,
                                     double max_rad) const {
  LoopClosureConfig c = config_.registration;
  c.max_correction_m = max_m;
  c.max_correction_rad = max_rad;
  std::vector<size_t> nodes = NodesNear(map_.nodes[node].T_map_imu.translation());
  if (nodes.empty()) nodes.push_back(node);
  const Eigen::Isometry3d guess =
      map_.nodes[node].T_map_imu.inverse() * T_map_imu_guess * keyframe.T_imu_lidar;
  return VerifyLoop(c, keyframe.planes_lidar, keyframe.edges_lidar, BuildSubmap(node, nodes),
                    guess);
}

}  // namespace swlio::estimator

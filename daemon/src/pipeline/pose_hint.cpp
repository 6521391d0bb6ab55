#include "swlio/daemon/pipeline/pose_hint.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

namespace swlio::daemon {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A σ from a variance: the default where the sender gives none (0, negative, not finite), and
/// never below a floor (a click is not more precise).
double SigmaOf(double variance, double fallback, double floor) {
  if (!std::isfinite(variance) || variance <= 0.0) return fallback;
  return std::max(std::sqrt(variance), floor);
}

std::string Fmt(const char* format, double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), format, a, b);
  return buf;
}

std::string Fmt(const char* format, double a) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, a);
  return buf;
}

}  // namespace

std::optional<PoseHint> HintFromInitialPose(const ipc::PoseWithCovarianceStamped& message,
                                            const std::string& map_frame,
                                            std::string* error) {
  if (message.frame_id != map_frame) {
    *error = "frame '" + message.frame_id + "' is not the map frame '" + map_frame + "'";
    return std::nullopt;
  }
  const auto& p = message.pose.position_m;
  const auto& q = message.pose.orientation_xyzw;
  const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  const double norm = rotation.norm();
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(norm) ||
      std::abs(norm - 1.0) > 0.01) {
    *error = "the pose is not finite or its orientation not a unit quaternion";
    return std::nullopt;
  }
  const Eigen::Matrix3d R = rotation.normalized().toRotationMatrix();
  PoseHint h;
  h.source = "/initialpose";
  h.x_m = p[0];
  h.y_m = p[1];
  h.yaw_rad = std::atan2(R(1, 0), R(0, 0));
  const auto& c = message.covariance;
  h.sigma_xy_m = SigmaOf(std::max(c[0], c[7]), PoseHint{}.sigma_xy_m, 0.05);
  h.sigma_yaw_rad = SigmaOf(c[35], PoseHint{}.sigma_yaw_rad, 0.02);
  return h;
}

std::optional<PoseHint> HintFromArgument(const std::string& argument, std::string* error) {
  std::istringstream in(argument);
  PoseHint h;
  h.source = "swlioctl";
  double yaw_deg = 0.0;
  if (!(in >> h.x_m >> h.y_m >> yaw_deg) || !std::isfinite(h.x_m) || !std::isfinite(h.y_m) ||
      !std::isfinite(yaw_deg)) {
    *error = "relocalize takes x y yaw (m, m, degrees) and an optional sigma (m)";
    return std::nullopt;
  }
  h.yaw_rad = std::remainder(yaw_deg * kDeg, 2.0 * std::numbers::pi);
  double sigma = 0.0;
  if (in >> sigma) {
    if (!std::isfinite(sigma) || sigma <= 0.0 || sigma > 100.0) {
      *error = "sigma must be in (0, 100] m";
      return std::nullopt;
    }
    h.sigma_xy_m = sigma;
  }
  std::string rest;
  if (in.clear(), in >> rest) {
    *error = "unexpected '" + rest + "' after relocalize's numbers";
    return std::nullopt;
  }
  return h;
}

estimator::LocalizationHint ImuHint(const PoseHint& hint, const Eigen::Isometry3d& T_base_imu) {
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
  T_map_base.linear() = Eigen::AngleAxisd(hint.yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
  T_map_base.translation() << hint.x_m, hint.y_m, 0.0;
  const Eigen::Isometry3d T_map_imu = T_map_base * T_base_imu;
  estimator::LocalizationHint h;
  h.x_m = T_map_imu.translation().x();
  h.y_m = T_map_imu.translation().y();
  h.yaw_rad = std::atan2(T_map_imu.linear()(1, 0), T_map_imu.linear()(0, 0));
  h.sigma_xy_m = hint.sigma_xy_m;
  h.sigma_yaw_rad = hint.sigma_yaw_rad;
  return h;
}

std::string DescribeHint(const PoseHint& hint, const estimator::HintOutcome& o) {
  using estimator::HintVerdict;
  const std::string at = Fmt("(%.2f, %.2f)", hint.x_m, hint.y_m);
  const std::string within =
      Fmt("within %.1f m / %.0f deg", 3.0 * hint.sigma_xy_m, 3.0 * hint.sigma_yaw_rad / kDeg);
  switch (o.verdict) {
    case HintVerdict::kTracking:
      return "localized at " + Fmt("(%.2f, %.2f)", o.p_map.x(), o.p_map.y()) +
             Fmt(" yaw %.1f deg (fitness %.2f)", o.yaw_map_rad / kDeg, o.check.fitness) +
             " from the hint at " + at;
    case HintVerdict::kConfirming:
      return "fits at " + Fmt("(%.2f, %.2f)", o.p_map.x(), o.p_map.y()) +
             " near the hint, and about as well at a look-alike place: confirming over the next "
             "keyframes";
    case HintVerdict::kNoMap:
      return "refused: the map's nearest node is " + Fmt("%.1f m", o.nearest_node_m) +
             " from the hint at " + at + ": outside the map";
    case HintVerdict::kNoFit:
      return "refused: the scan does not fit the map " + within + " of " + at +
             " (best: " + estimator::ToString(o.check.verdict) +
             Fmt(", fitness %.2f, moved %.1f m)", o.check.fitness, o.check.correction_m);
    case HintVerdict::kElsewhere:
      return "refused: the scan fits " + Fmt("(%.2f, %.2f)", o.p_elsewhere.x(), o.p_elsewhere.y()) +
             Fmt(" better (fitness %.2f against %.2f)", o.fitness_elsewhere, o.check.fitness) +
             " than anywhere " + within + " of " + at;
    case HintVerdict::kNoKeyframe:
      return "refused: no scan to register yet (the estimator has not started)";
  }
  return "?";
}

}  // namespace swlio::daemon

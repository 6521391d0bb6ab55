// GNSS fixes → pose-graph observations: see gnss_associator.h.

#include "swlio/estimator/gnss/gnss_associator.h"

#include <algorithm>
#include <cmath>

#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

/// Keeps this much odometry for placing waiting fixes.
constexpr int64_t kKeepOdometryNs = 30 * kNsPerSec;
/// Fixes waiting for the odometry, at most (10 min at 1 Hz).
constexpr size_t kMaxPending = 600;

}  // namespace

GnssAssociator::GnssAssociator(const GnssConfig& config)
    : config_(config),
      inflation_(std::sqrt(
          std::max(1.0, config.correlation_time_s / std::max(config.min_interval_s, 1e-3)))) {
  if (config_.has_origin()) {
    origin_ = Geodetic{config_.origin_lat_deg, config_.origin_lon_deg, config_.origin_height_m};
    enu_.emplace(*origin_);
  }
}

bool GnssAssociator::Accept(const GnssFix& fix) {
  const bool finite = std::isfinite(fix.lat_deg) && std::isfinite(fix.lon_deg) &&
                      std::isfinite(fix.height_m) && std::isfinite(fix.h_acc_m) &&
                      std::isfinite(fix.v_acc_m);
  const bool plausible = finite && std::abs(fix.lat_deg) <= 90.0 &&
                         std::abs(fix.lon_deg) <= 180.0 && std::abs(fix.height_m) < 1e5 &&
                         fix.h_acc_m >= 0.0 && fix.v_acc_m >= 0.0;
  if (!plausible || fix.fix_type < config_.min_fix_type || fix.h_acc_m > config_.max_h_acc_m) {
    ++stats_.bad_quality;
    return false;
  }
  const auto interval_ns = static_cast<int64_t>(config_.min_interval_s * 1e9);
  if (taken_any_ && fix.t_ns - last_taken_t_ns_ < interval_ns) {
    ++stats_.rate_limited;
    return false;
  }
  return true;
}

void GnssAssociator::AddFix(const GnssFix& fix) {
  ++stats_.fixes;
  if (!Accept(fix)) return;
  const Geodetic g{fix.lat_deg, fix.lon_deg, fix.height_m};
  if (!enu_) {
    origin_ = g;
    enu_.emplace(g);
  }
  taken_any_ = true;
  last_taken_t_ns_ = fix.t_ns;
  const double sigma_h =
      std::max(config_.min_sigma_m, config_.sigma_scale * fix.h_acc_m) * inflation_;
  const double sigma_v =
      std::max(config_.min_sigma_m, config_.sigma_scale * fix.v_acc_m) * inflation_;
  pending_.push_back({fix.t_ns, enu_->ToEnu(g), sigma_h, sigma_v});
  if (pending_.size() > kMaxPending) {  // the odometry stopped (standing robot, lost LiDAR)
    pending_.pop_front();
    ++stats_.unplaced;
  }
}

void GnssAssociator::AddOdometry(int64_t t_ns, const Eigen::Isometry3d& T_odom_imu) {
  if (!odometry_.empty() && t_ns <= odometry_.end_ns()) return;
  odometry_.Add(t_ns, T_odom_imu);
  odometry_.DropBefore(t_ns - kKeepOdometryNs);
}

std::vector<GnssObservation> GnssAssociator::Take(std::span<const KeyframeCloud> nodes) {
  std::vector<GnssObservation> out;
  while (!pending_.empty() && !odometry_.empty() && pending_.front().t_ns <= odometry_.end_ns()) {
    const Pending p = pending_.front();
    pending_.pop_front();
    const auto node =
        std::upper_bound(nodes.begin(), nodes.end(), p.t_ns,
                         [](int64_t t, const KeyframeCloud& n) { return t < n.t_ns; });
    // The odometry at the fix's time, between keyframes at most max_interpolation_s apart.
    Eigen::Isometry3d T_odom_imu;
    const auto max_gap_ns = static_cast<int64_t>(config_.max_interpolation_s * 1e9);
    if (node == nodes.begin() || !odometry_.At(p.t_ns, max_gap_ns, &T_odom_imu)) {
      ++stats_.unplaced;
      continue;
    }
    const KeyframeCloud& n = *(node - 1);
    GnssObservation o;
    o.t_ns = p.t_ns;
    o.node = static_cast<size_t>(node - nodes.begin()) - 1;
    o.antenna_imu_m = n.T_world_imu.inverse() * (T_odom_imu * config_.antenna_imu_m);
    o.fix_enu_m = p.enu_m;
    o.sigma_h_m = p.sigma_h_m;
    o.sigma_v_m = p.sigma_v_m;
    o.inflation = inflation_;
    out.push_back(o);
    ++stats_.observations;
  }
  return out;
}

Eigen::Isometry3d FitEnuAlignment(std::span<const Eigen::Vector3d> map_m,
                                  std::span<const Eigen::Vector3d> enu_m) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const size_t n = std::min(map_m.size(), enu_m.size());
  if (n == 0) return T;
  Eigen::Vector3d mean_map = Eigen::Vector3d::Zero(), mean_enu = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    mean_map += map_m[i];
    mean_enu += enu_m[i];
  }
  mean_map /= static_cast<double>(n);
  mean_enu /= static_cast<double>(n);
  // Yaw maximizing Σ b·Rz a over the centred horizontal coordinates: atan2(Σ a×b, Σ a·b).
  double cross = 0.0, dot = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = (map_m[i] - mean_map).head<2>();
    const Eigen::Vector2d b = (enu_m[i] - mean_enu).head<2>();
    cross += a.x() * b.y() - a.y() * b.x();
    dot += a.dot(b);
  }
  T.linear() =
      Eigen::AngleAxisd(std::atan2(cross, dot), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = mean_enu - T.linear() * mean_map;
  return T;
}

}  // namespace swlio::estimator

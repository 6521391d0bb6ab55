#include "swlio/estimator/map/visibility_image.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "swlio/estimator/frontend/range_image.h"

namespace swlio::estimator {
namespace {

/// Returns nearer than this are not kept (the sensor's own housing).
constexpr float kMinReturnM = 0.1f;
/// Added to a point's angle off its beam when the ground's range slope is applied: the pose's
/// and the beam's own angular error (the RS16's vertical beam spacing is 2°, its divergence
/// about 3 mrad).
constexpr float kAngleSlackRad = 0.002f;
/// Columns searched on each side of a point's own at most.
constexpr int kMaxHalfColumns = 8;

float Elevation(const Eigen::Vector3f& q) {
  return FastAtan2(q.z(), std::sqrt(q.x() * q.x() + q.y() * q.y()));
}

}  // namespace

ConfigIssues VisibilityConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange<int64_t>(issues, "rings", rings, 2, 64);
  CheckInRange<int64_t>(issues, "columns", columns, 36, 36000);
  CheckInRange(issues, "min_range_m", min_range_m, 0.0, 10.0);
  CheckInRange(issues, "max_range_m", max_range_m, 1.0, 1000.0);
  CheckThat(issues, min_range_m < max_range_m, "max_range_m", "must exceed min_range_m");
  CheckInRange(issues, "beam_tolerance_m", beam_tolerance_m, 0.01, 1.0);
  CheckInRange(issues, "margin_m", margin_m, 0.01, 5.0);
  CheckInRange(issues, "margin_ratio", margin_ratio, 0.0, 0.5);
  CheckInRange<int64_t>(issues, "neighbour_columns", neighbour_columns, 0, kMaxHalfColumns);
  CheckInRange<int64_t>(issues, "votes_to_remove", votes_to_remove, 1, 100);
  CheckInRange(issues, "check_radius_m", check_radius_m, 1.0, 1000.0);
  return issues;
}

VisibilityImage::VisibilityImage(const VisibilityConfig& config)
    : config_(config),
      rings_(static_cast<int>(config.rings)),
      columns_(static_cast<int>(config.columns)),
      range_cm_(static_cast<size_t>(config.rings * config.columns), 0),
      ring_elevation_rad_(static_cast<size_t>(config.rings), 0.0f),
      ring_seen_(static_cast<size_t>(config.rings), 0) {}

void VisibilityImage::Build(std::span<const LidarPoint> points_lidar,
                            const Eigen::Isometry3d& T_world_lidar) {
  T_world_lidar_ = T_world_lidar;
  T_lidar_world_ = T_world_lidar.inverse();
  std::fill(range_cm_.begin(), range_cm_.end(), uint16_t{0});
  std::vector<double> sum(static_cast<size_t>(rings_), 0.0);
  std::vector<int64_t> count(static_cast<size_t>(rings_), 0);
  const float columns_per_rad = static_cast<float>(columns_) / (2.0f * std::numbers::pi_v<float>);
  for (const LidarPoint& p : points_lidar) {
    if (p.ring >= rings_) continue;
    const float range = p.xyz_m.norm();
    if (!(range > kMinReturnM) || !std::isfinite(range)) continue;
    const float azimuth = FastAtan2(-p.xyz_m.y(), p.xyz_m.x()) + std::numbers::pi_v<float>;
    const int column = std::clamp(static_cast<int>(azimuth * columns_per_rad), 0, columns_ - 1);
    uint16_t& cell = range_cm_[static_cast<size_t>(p.ring) * static_cast<size_t>(columns_) +
                               static_cast<size_t>(column)];
    const auto cm = static_cast<uint16_t>(std::clamp(std::lround(range * 100.0f), 1L, 65535L));
    if (cell == 0 || cm < cell) cell = cm;
    sum[p.ring] += Elevation(p.xyz_m);
    ++count[p.ring];
  }
  for (size_t r = 0; r < sum.size(); ++r) {
    ring_seen_[r] = count[r] > 0 ? 1 : 0;
    ring_elevation_rad_[r] =
        count[r] > 0 ? static_cast<float>(sum[r] / static_cast<double>(count[r])) : 0.0f;
  }
}

int VisibilityImage::NearestRing(float elevation_rad) const {
  int best = -1;
  float best_off = std::numeric_limits<float>::infinity();
  for (int r = 0; r < rings_; ++r) {
    if (!ring_seen_[static_cast<size_t>(r)]) continue;
    const float off = std::abs(elevation_rad - ring_elevation_rad_[static_cast<size_t>(r)]);
    if (off < best_off) {
      best_off = off;
      best = r;
    }
  }
  return best;
}

float VisibilityImage::SlopeAt(int ring, int column) const {
  const float here = RangeAt(ring, column);
  float slope = -1.0f;
  for (const int other : {ring - 1, ring + 1}) {
    if (other < 0 || other >= rings_ || !ring_seen_[static_cast<size_t>(other)]) continue;
    const float there = RangeAt(other, column);
    if (there == 0.0f) continue;
    const float d_elevation = std::abs(ring_elevation_rad_[static_cast<size_t>(other)] -
                                       ring_elevation_rad_[static_cast<size_t>(ring)]);
    if (d_elevation <= 0.0f) continue;
    // The secant between two rings underestimates the slope at the farther return where the
    // range grows faster than linearly (the ground: r = h / θ, dr/dθ = r² / h, which is the
    // secant times r_far / r_near there); scaled up by that ratio, which is 1 on a wall.
    const float secant = std::abs(there - here) / d_elevation;
    slope = std::max(slope, secant * std::max(here, there) / std::min(here, there));
  }
  return slope;
}

Visibility VisibilityImage::Test(const Eigen::Vector3d& p_world) const {
  const Eigen::Vector3f q = (T_lidar_world_ * p_world).cast<float>();
  const float range = q.norm();
  if (!(range >= config_.min_range_m && range <= config_.max_range_m)) {
    return Visibility::kUnknown;
  }
  const float elevation = Elevation(q);
  const int ring = NearestRing(elevation);
  if (ring < 0) return Visibility::kUnknown;
  const float off_rad = std::abs(elevation - ring_elevation_rad_[static_cast<size_t>(ring)]);
  const auto tolerance_m = static_cast<float>(config_.beam_tolerance_m);
  if (off_rad * range > tolerance_m) return Visibility::kUnknown;

  // The nearest return of the ring in the columns around the point's.
  const float column_rad = 2.0f * std::numbers::pi_v<float> / static_cast<float>(columns_);
  const float azimuth = FastAtan2(-q.y(), q.x()) + std::numbers::pi_v<float>;
  const int column = std::clamp(static_cast<int>(azimuth / column_rad), 0, columns_ - 1);
  const int half =
      std::clamp(std::max(static_cast<int>(config_.neighbour_columns),
                          static_cast<int>(std::ceil(tolerance_m / range / column_rad))),
                 0, kMaxHalfColumns);
  float nearest = std::numeric_limits<float>::infinity();
  int nearest_column = -1;
  for (int dc = -half; dc <= half; ++dc) {
    const int c = (column + dc + columns_) % columns_;
    const float m = RangeAt(ring, c);
    if (m > 0.0f && m < nearest) {
      nearest = m;
      nearest_column = c;
    }
  }
  if (nearest_column < 0) return Visibility::kUnknown;  // no return: no evidence
  const auto band = static_cast<float>(config_.margin_m + config_.margin_ratio * range);
  if (std::abs(nearest - range) <= band) return Visibility::kConfirmed;
  if (nearest < range) return Visibility::kUnknown;  // occluded
  const float slope = SlopeAt(ring, nearest_column);
  if (slope < 0.0f) return Visibility::kUnknown;  // no ring beside it: grazing unknown
  return nearest > range + band + slope * (off_rad + kAngleSlackRad) ? Visibility::kSeenThrough
                                                                     : Visibility::kUnknown;
}

}  // namespace swlio::estimator

#include "swlio/estimator/frontend/range_image.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swlio::estimator {

// atan2 from an 11th-order odd minimax polynomial for atan on [−1, 1] (|error| < 1e-5 rad =
// 0.0006°, against 0.2° columns) and octant folding; several times cheaper than std::atan2.
float FastAtan2(float y, float x) {
  const float ax = std::abs(x);
  const float ay = std::abs(y);
  const float mx = std::max(ax, ay);
  if (mx == 0.0f) return 0.0f;
  const float z = std::min(ax, ay) / mx;
  const float z2 = z * z;
  float a =
      z *
      (0.99997726f +
       z2 * (-0.33262347f +
             z2 * (0.19354346f + z2 * (-0.11643287f + z2 * (0.05265332f + z2 * -0.01172120f)))));
  if (ay > ax) a = std::numbers::pi_v<float> / 2.0f - a;
  if (x < 0.0f) a = std::numbers::pi_v<float> - a;
  return y < 0.0f ? -a : a;
}

ConfigIssues RangeImageConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange<int64_t>(issues, "rings", rings, 2, 64);
  CheckInRange<int64_t>(issues, "columns", columns, 36, 36000);
  CheckInRange(issues, "min_range_m", min_range_m, 0.0, 10.0);
  CheckInRange(issues, "max_range_m", max_range_m, 1.0, 1000.0);
  CheckThat(issues, min_range_m < max_range_m, "max_range_m", "must exceed min_range_m");
  return issues;
}

RangeImage::RangeImage(const RangeImageConfig& config)
    : config_(config),
      rings_(static_cast<int>(config.rings)),
      columns_(static_cast<int>(config.columns)),
      columns_per_rad_(
          static_cast<float>(static_cast<double>(config.columns) / (2.0 * std::numbers::pi))) {
  const auto cells = static_cast<size_t>(rings_) * static_cast<size_t>(columns_);
  index_.assign(cells, kEmpty);
  range_m_.assign(cells, 0.0f);
  xyz_m_.assign(cells, Eigen::Vector3f::Zero());
}

int RangeImage::Column(const Eigen::Vector3f& xyz_m) const {
  // Azimuth clockwise from +x (forward) seen from above, as the LiDAR turns, shifted to
  // [0, 2π): column 0 is behind the sensor.
  const float azimuth = FastAtan2(-xyz_m.y(), xyz_m.x()) + std::numbers::pi_v<float>;
  const int column = static_cast<int>(azimuth * columns_per_rad_);
  return std::clamp(column, 0, columns_ - 1);
}

RangeImageStats RangeImage::Build(std::span<const LidarPoint> points) {
  std::fill(index_.begin(), index_.end(), kEmpty);
  std::fill(range_m_.begin(), range_m_.end(), 0.0f);
  RangeImageStats stats;
  const auto min_r = static_cast<float>(config_.min_range_m);
  const auto max_r = static_cast<float>(config_.max_range_m);
  for (size_t i = 0; i < points.size(); ++i) {
    const LidarPoint& p = points[i];
    if (p.ring >= rings_) {
      ++stats.bad_ring;
      continue;
    }
    const float range = p.xyz_m.norm();
    if (!(range >= min_r && range <= max_r)) {
      ++stats.out_of_range;
      continue;
    }
    const int column = Column(p.xyz_m);
    auto cell = static_cast<size_t>(Cell(p.ring, column));
    if (index_[cell] != kEmpty) {
      // Motion de-skew bunches azimuths: a free neighbouring column takes the point first.
      const auto next = static_cast<size_t>(Cell(p.ring, (column + 1) % columns_));
      const auto prev = static_cast<size_t>(Cell(p.ring, (column + columns_ - 1) % columns_));
      if (index_[next] == kEmpty) {
        cell = next;
      } else if (index_[prev] == kEmpty) {
        cell = prev;
      }
    }
    if (index_[cell] != kEmpty) {
      ++stats.collisions;
      if (range >= range_m_[cell]) continue;
    } else {
      ++stats.placed;
    }
    index_[cell] = static_cast<int32_t>(i);
    range_m_[cell] = range;
    xyz_m_[cell] = p.xyz_m;
  }
  return stats;
}

}  // namespace swlio::estimator

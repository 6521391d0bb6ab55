#include "swlio/estimator/frontend/segmentation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace swlio::estimator {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

}  // namespace

ConfigIssues SegmentationConfig::Validate() const {
  ConfigIssues issues;
  AppendWithPrefix(issues, "image", image.Validate());
  CheckInRange<int64_t>(issues, "ground_max_ring", ground_max_ring, 0, image.rings - 1);
  CheckInRange(issues, "ground_max_slope_deg", ground_max_slope_deg, 0.5, 45.0);
  CheckInRange<int64_t>(issues, "ground_max_missing_rings", ground_max_missing_rings, 0,
                        image.rings - 2);
  CheckInRange(issues, "ground_foot_gap_m", ground_foot_gap_m, 0.0, 2.0);
  CheckInRange(issues, "mount_roll_deg", mount_roll_deg, -30.0, 30.0);
  CheckInRange(issues, "mount_pitch_deg", mount_pitch_deg, -30.0, 30.0);
  CheckInRange(issues, "cluster_angle_deg", cluster_angle_deg, 1.0, 89.0);
  CheckInRange<int64_t>(issues, "min_cluster_points", min_cluster_points, 1, 100000);
  CheckInRange<int64_t>(issues, "min_cluster_rings", min_cluster_rings, 1, image.rings);
  CheckInRange<int64_t>(issues, "min_spanning_cluster_points", min_spanning_cluster_points, 1,
                        100000);
  return issues;
}

Segmenter::Segmenter(const SegmentationConfig& config)
    : config_(config),
      image_(config.image),
      tan_ground_(static_cast<float>(std::tan(config.ground_max_slope_deg * kDegToRad))),
      tan_cluster_(static_cast<float>(std::tan(config.cluster_angle_deg * kDegToRad))),
      foot_gap_m_(static_cast<float>(config.ground_foot_gap_m)) {
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(config.mount_pitch_deg * kDegToRad, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(config.mount_roll_deg * kDegToRad, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  R_level_lidar_mount_ = R.cast<float>();
  R_level_lidar_ = R_level_lidar_mount_;
  const auto cells = static_cast<size_t>(image_.rings()) * static_cast<size_t>(image_.columns());
  cell_label_.assign(cells, 0);
  queue_.assign(cells, 0);
}

void Segmenter::Segment(const Scan& scan, SegmentationResult* result) {
  Segment(scan, R_level_lidar_mount_, result);
}

void Segmenter::Segment(const Scan& scan,
                        const Eigen::Matrix3f& R_level_lidar,
                        SegmentationResult* result) {
  R_level_lidar_ = R_level_lidar;
  result->image = image_.Build(scan.points);
  std::fill(cell_label_.begin(), cell_label_.end(), 0);
  clusters_ = 0;
  outliers_ = 0;
  MarkGround();
  Cluster();
  Collect(scan, result);
}

// Ground (LeGO-LOAM): for each column, the ring pair (r, r+1) is ground when the levelled
// difference vector rises less than ground_max_slope_deg; both cells are marked. Where ring
// r+1 has no return in the column, r pairs with the next ring up that has one (at most
// ground_max_missing_rings skipped, up to ground_max_ring): a lone missing return then costs
// only its own point, not also the ground label of its neighbours above and below.
void Segmenter::MarkGround() {
  const int columns = image_.columns();
  const int max_ring = static_cast<int>(config_.ground_max_ring);
  const int max_skip = static_cast<int>(config_.ground_max_missing_rings);
  for (int c = 0; c < columns; ++c) {
    for (int r = 0; r < max_ring; ++r) {
      const int lower = image_.Cell(r, c);
      if (image_.Index(lower) == RangeImage::kEmpty) continue;
      int upper_ring = r + 1;
      while (upper_ring < max_ring && upper_ring - r <= max_skip &&
             image_.Index(image_.Cell(upper_ring, c)) == RangeImage::kEmpty) {
        ++upper_ring;
      }
      const int upper = image_.Cell(upper_ring, c);
      if (image_.Index(upper) == RangeImage::kEmpty) continue;
      const Eigen::Vector3f d = R_level_lidar_ * (image_.Xyz(upper) - image_.Xyz(lower));
      if (std::abs(d.z()) <= tan_ground_ * d.head<2>().norm()) {
        cell_label_[static_cast<size_t>(lower)] = kLabelGround;
        cell_label_[static_cast<size_t>(upper)] = kLabelGround;
      }
    }
    UnmarkWallFeet(c);
  }
}

// A beam that grazes the foot of a wall far away makes a shallow pair with the ground point
// below it (the long horizontal gap hides the height), so the pair test alone calls it ground.
// Such a point is the lower end of a near-vertical pair with the ring above: horizontally
// within ground_foot_gap_m of it and rising steeply. Those points are taken off the ground.
void Segmenter::UnmarkWallFeet(int column) {
  if (foot_gap_m_ <= 0.0f) return;
  const int max_ring = static_cast<int>(config_.ground_max_ring);
  for (int r = 1; r <= max_ring && r + 1 < image_.rings(); ++r) {
    const int cell = image_.Cell(r, column);
    const int above = image_.Cell(r + 1, column);
    if (cell_label_[static_cast<size_t>(cell)] != kLabelGround) continue;
    if (image_.Index(above) == RangeImage::kEmpty) continue;
    const Eigen::Vector3f a = R_level_lidar_ * image_.Xyz(cell);
    const Eigen::Vector3f b = R_level_lidar_ * image_.Xyz(above);
    const float gap = std::abs(b.head<2>().norm() - a.head<2>().norm());
    const float rise = b.z() - a.z();
    if (gap <= foot_gap_m_ && rise > tan_ground_ * gap) {
      cell_label_[static_cast<size_t>(cell)] = 0;
    }
  }
}

// β of eq. (13): with d1 = |p1| ≥ d2 = |p2| and α the angle between the two beams,
//   β = atan(d2·sin α / (d1 − d2·cos α)).
// Multiplying through by d1 and using d1·d2·sin α = |p1 × p2|, d1·d2·cos α = p1·p2 gives
//   β = atan2(|p1 × p2|, d1² − p1·p2),
// exact for any pair of beams (no nominal resolution needed) and free of trigonometry.
// Same object when β > cluster_angle_deg.
bool Segmenter::SameObject(int cell_a, int cell_b) const {
  const bool a_far = image_.Range(cell_a) >= image_.Range(cell_b);
  const Eigen::Vector3f& p1 = image_.Xyz(a_far ? cell_a : cell_b);
  const Eigen::Vector3f& p2 = image_.Xyz(a_far ? cell_b : cell_a);
  const float denominator = p1.squaredNorm() - p1.dot(p2);
  if (denominator <= 0.0f) return true;  // β ≥ 90°
  const float bound = tan_cluster_ * denominator;
  return p1.cross(p2).squaredNorm() > bound * bound;
}

int Segmenter::Grow(int seed, int32_t label, uint64_t* ring_mask) {
  const int rings = image_.rings();
  const int columns = image_.columns();
  int head = 0;
  int tail = 0;
  queue_[static_cast<size_t>(tail++)] = seed;
  cell_label_[static_cast<size_t>(seed)] = label;
  *ring_mask = 0;
  while (head < tail) {
    const int cell = queue_[static_cast<size_t>(head++)];
    const int r = cell / columns;
    const int c = cell % columns;
    *ring_mask |= uint64_t{1} << r;
    const int neighbours[4] = {r > 0 ? cell - columns : -1, r + 1 < rings ? cell + columns : -1,
                               r * columns + (c + columns - 1) % columns,
                               r * columns + (c + 1) % columns};
    for (const int n : neighbours) {
      if (n < 0 || image_.Index(n) == RangeImage::kEmpty) continue;
      if (cell_label_[static_cast<size_t>(n)] != 0) continue;
      if (!SameObject(cell, n)) continue;
      cell_label_[static_cast<size_t>(n)] = label;
      queue_[static_cast<size_t>(tail++)] = n;
    }
  }
  return tail;
}

void Segmenter::Cluster() {
  const int cells = image_.rings() * image_.columns();
  for (int cell = 0; cell < cells; ++cell) {
    if (image_.Index(cell) == RangeImage::kEmpty || cell_label_[static_cast<size_t>(cell)] != 0) {
      continue;
    }
    uint64_t ring_mask = 0;
    const int32_t label = clusters_ + 1;
    const int size = Grow(cell, label, &ring_mask);
    const int rings_spanned = std::popcount(ring_mask);
    const bool keep =
        size >= config_.min_cluster_points ||
        (rings_spanned >= config_.min_cluster_rings && size >= config_.min_spanning_cluster_points);
    if (keep) {
      clusters_ = label;
      continue;
    }
    for (int i = 0; i < size; ++i)
      cell_label_[static_cast<size_t>(queue_[static_cast<size_t>(i)])] = kLabelOutlier;
    outliers_ += size;
  }
}

void Segmenter::Collect(const Scan& scan, SegmentationResult* result) const {
  result->labels.assign(scan.points.size(), kLabelInvalid);
  result->points.clear();
  result->points.reserve(cell_label_.size());
  result->ring_begin.clear();
  result->ground_points = 0;
  for (int r = 0; r < image_.rings(); ++r) {
    result->ring_begin.push_back(static_cast<uint32_t>(result->points.size()));
    for (int c = 0; c < image_.columns(); ++c) {
      const int cell = image_.Cell(r, c);
      const int32_t index = image_.Index(cell);
      if (index == RangeImage::kEmpty) continue;
      const int32_t label = cell_label_[static_cast<size_t>(cell)];
      result->labels[static_cast<size_t>(index)] = label;
      if (label == kLabelOutlier) continue;
      if (label == kLabelGround) ++result->ground_points;
      const LidarPoint& p = scan.points[static_cast<size_t>(index)];
      result->points.push_back({p.xyz_m, image_.Range(cell), p.dt_ns, static_cast<uint32_t>(index),
                                label, static_cast<uint16_t>(r), static_cast<uint16_t>(c)});
    }
  }
  result->ring_begin.push_back(static_cast<uint32_t>(result->points.size()));
  result->clusters = clusters_;
  result->outlier_points = outliers_;
}

}  // namespace swlio::estimator

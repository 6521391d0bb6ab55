#include "swlio/estimator/loop/scan_context.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swlio::estimator {
namespace {

size_t CellCount(int rings, int sectors) {
  return static_cast<size_t>(std::max(rings, 0)) * static_cast<size_t>(std::max(sectors, 0));
}

/// Bins one gravity-frame point into `cells` (row-major rings × sectors), keeping the max
/// height. Points outside [min_range_m, max_range_m) horizontally, or not finite, are skipped.
void BinPoint(const ScanContextConfig& config,
              const Eigen::Vector3d& p_gravity,
              std::vector<float>& cells) {
  if (!p_gravity.allFinite()) return;
  const double range_m = std::hypot(p_gravity.x(), p_gravity.y());
  if (!(range_m >= config.min_range_m && range_m < config.max_range_m)) return;
  const int ring = std::min(
      static_cast<int>(std::floor(range_m / config.max_range_m * config.rings)), config.rings - 1);
  const double azimuth_rad = std::atan2(p_gravity.y(), p_gravity.x());  // [−π, π]
  const double turns = (azimuth_rad + std::numbers::pi) / (2.0 * std::numbers::pi);
  const int sector =
      std::clamp(static_cast<int>(std::floor(turns * config.sectors)), 0, config.sectors - 1);
  const float height_m = static_cast<float>(std::max(p_gravity.z() + config.height_offset_m, 0.0));
  float& cell = cells[static_cast<size_t>(ring) * static_cast<size_t>(config.sectors) +
                      static_cast<size_t>(sector)];
  cell = std::max(cell, height_m);
}

/// Euclidean norm of each column.
std::vector<float> ColumnNorms(const ScanContext& sc) {
  const size_t n = static_cast<size_t>(sc.sectors);
  std::vector<float> norms(n, 0.0f);
  for (size_t r = 0; r < static_cast<size_t>(sc.rings); ++r) {
    const float* row = sc.cells.data() + r * n;
    for (size_t j = 0; j < n; ++j) norms[j] += row[j] * row[j];
  }
  for (float& v : norms) v = std::sqrt(v);
  return norms;
}

/// Eq. (5) for one shift s: mean of (1 − cos) over the column pairs (j, (j + s) mod n) where
/// both columns are non-empty; `dots` is scratch of n values. Returns 1 when none compares.
float ShiftDistance(const ScanContext& query,
                    const ScanContext& candidate,
                    const std::vector<float>& query_norms,
                    const std::vector<float>& candidate_norms,
                    size_t shift,
                    std::vector<float>& dots) {
  const size_t n = static_cast<size_t>(query.sectors);
  std::fill(dots.begin(), dots.end(), 0.0f);
  // Two contiguous runs per row (before and after the wrap) so the inner loops vectorize.
  for (size_t r = 0; r < static_cast<size_t>(query.rings); ++r) {
    const float* q = query.cells.data() + r * n;
    const float* c = candidate.cells.data() + r * n;
    for (size_t j = 0; j < n - shift; ++j) dots[j] += q[j] * c[j + shift];
    for (size_t j = n - shift; j < n; ++j) dots[j] += q[j] * c[j + shift - n];
  }
  float sum = 0.0f;
  int count = 0;
  for (size_t j = 0; j < n; ++j) {
    const float norm_product = query_norms[j] * candidate_norms[(j + shift) % n];
    if (norm_product <= 0.0f) continue;
    sum += 1.0f - dots[j] / norm_product;
    ++count;
  }
  if (count == 0) return 1.0f;
  return std::clamp(sum / static_cast<float>(count), 0.0f, 1.0f);
}

}  // namespace

ConfigIssues ScanContextConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "rings", rings, 1, 1000);
  CheckInRange(issues, "sectors", sectors, 3, 3600);
  CheckPositive(issues, "max_range_m", max_range_m);
  CheckInRange(issues, "min_range_m", min_range_m, 0.0, 1e4);
  CheckThat(issues, max_range_m > min_range_m, "max_range_m", "must exceed min_range_m");
  CheckInRange(issues, "height_offset_m", height_offset_m, 0.0, 100.0);
  CheckInRange(issues, "candidates", candidates, 1, 100000);
  CheckThat(issues, max_distance > 0.0 && max_distance <= 1.0, "max_distance", "must be in (0, 1]");
  return issues;
}

ScanContext ScanContextFromCells(int rings, int sectors, std::vector<float> cells) {
  ScanContext sc;
  sc.rings = rings;
  sc.sectors = sectors;
  sc.cells = std::move(cells);
  sc.ring_key.assign(static_cast<size_t>(std::max(rings, 0)), 0.0f);
  if (sc.cells.size() != CellCount(rings, sectors)) return sc;
  for (int r = 0; r < rings; ++r) {
    int occupied = 0;
    for (int s = 0; s < sectors; ++s) occupied += sc.at(r, s) > 0.0f ? 1 : 0;
    sc.ring_key[static_cast<size_t>(r)] =
        static_cast<float>(occupied) / static_cast<float>(sectors);
  }
  return sc;
}

ScanContext MakeScanContext(const ScanContextConfig& config,
                            const std::vector<Eigen::Vector3d>& points_gravity) {
  std::vector<float> cells(CellCount(config.rings, config.sectors), 0.0f);
  for (const Eigen::Vector3d& p : points_gravity) BinPoint(config, p, cells);
  return ScanContextFromCells(config.rings, config.sectors, std::move(cells));
}

ScanContext MakeScanContext(const ScanContextConfig& config,
                            const Eigen::Isometry3d& T_gravity_lidar,
                            const std::vector<Eigen::Vector3d>& points_lidar) {
  std::vector<float> cells(CellCount(config.rings, config.sectors), 0.0f);
  for (const Eigen::Vector3d& p : points_lidar) BinPoint(config, T_gravity_lidar * p, cells);
  return ScanContextFromCells(config.rings, config.sectors, std::move(cells));
}

Eigen::Matrix3d GravityAlignedFromBody(const Eigen::Matrix3d& R_world_body) {
  // Heading = azimuth of the body's x axis in the world; removing it leaves roll and pitch.
  const Eigen::Vector3d x_world = R_world_body.col(0);
  const double yaw_rad =
      (x_world.x() == 0.0 && x_world.y() == 0.0) ? 0.0 : std::atan2(x_world.y(), x_world.x());
  return Eigen::AngleAxisd(-yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_world_body;
}

ScanContextMatch CompareScanContexts(const ScanContext& query, const ScanContext& candidate) {
  ScanContextMatch best;
  const size_t cell_count = CellCount(query.rings, query.sectors);
  if (query.rings != candidate.rings || query.sectors != candidate.sectors || query.sectors <= 0 ||
      query.rings <= 0 || query.cells.size() != cell_count ||
      candidate.cells.size() != cell_count) {
    return best;
  }
  const std::vector<float> query_norms = ColumnNorms(query);
  const std::vector<float> candidate_norms = ColumnNorms(candidate);
  std::vector<float> dots(static_cast<size_t>(query.sectors));
  float best_distance = 2.0f;
  for (int shift = 0; shift < query.sectors; ++shift) {
    const float d = ShiftDistance(query, candidate, query_norms, candidate_norms,
                                  static_cast<size_t>(shift), dots);
    if (d < best_distance) {
      best_distance = d;
      best.shift = shift;
    }
  }
  best.distance = static_cast<double>(best_distance);
  const int signed_shift = best.shift > query.sectors / 2 ? best.shift - query.sectors : best.shift;
  best.yaw_rad = signed_shift * 2.0 * std::numbers::pi / query.sectors;
  return best;
}

ScanContextDatabase::ScanContextDatabase(const ScanContextConfig& config) : config_(config) {}

size_t ScanContextDatabase::Add(ScanContext descriptor) {
  descriptors_.push_back(std::move(descriptor));
  return descriptors_.size() - 1;
}

std::vector<std::pair<size_t, ScanContextMatch>> ScanContextDatabase::Query(
    const ScanContext& query,
    size_t max_results,
    const std::function<bool(size_t)>& allowed) const {
  // Ring-key nearest neighbours (squared Euclidean distance, ties by index).
  std::vector<std::pair<float, size_t>> by_key;
  for (size_t i = 0; i < descriptors_.size(); ++i) {
    const ScanContext& sc = descriptors_[i];
    if (sc.rings != query.rings || sc.sectors != query.sectors) continue;
    if (sc.ring_key.size() != query.ring_key.size()) continue;
    if (allowed && !allowed(i)) continue;
    float d2 = 0.0f;
    for (size_t r = 0; r < query.ring_key.size(); ++r) {
      const float diff = sc.ring_key[r] - query.ring_key[r];
      d2 += diff * diff;
    }
    by_key.emplace_back(d2, i);
  }
  const size_t n_candidates =
      std::min(by_key.size(), static_cast<size_t>(std::max(config_.candidates, 0)));
  std::partial_sort(by_key.begin(), by_key.begin() + static_cast<std::ptrdiff_t>(n_candidates),
                    by_key.end());

  std::vector<std::pair<size_t, ScanContextMatch>> matches;
  for (size_t k = 0; k < n_candidates; ++k) {
    const size_t i = by_key[k].second;
    const ScanContextMatch match = CompareScanContexts(query, descriptors_[i]);
    if (match.distance < config_.max_distance) matches.emplace_back(i, match);
  }
  std::sort(matches.begin(), matches.end(), [](const auto& a, const auto& b) {
    if (a.second.distance != b.second.distance) return a.second.distance < b.second.distance;
    return a.first < b.first;
  });
  if (matches.size() > max_results) matches.resize(max_results);
  return matches;
}

}  // namespace swlio::estimator

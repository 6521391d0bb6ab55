#include "swlio/estimator/registration/voxel_map.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <utility>

namespace swlio::estimator {

ConfigIssues VoxelMapConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "voxel_m", voxel_m, 0.1, 10.0);
  CheckInRange<size_t>(issues, "max_points_per_voxel", max_points_per_voxel, 1, 1000);
  CheckInRange(issues, "min_point_spacing_m", min_point_spacing_m, 0.0, 5.0);
  CheckInRange(issues, "radius_m", radius_m, 5.0, 1000.0);
  return issues;
}

namespace {

uint64_t NextRevision() {
  static std::atomic<uint64_t> last{0};
  return last.fetch_add(1, std::memory_order_relaxed) + 1;
}

}  // namespace

VoxelMap::VoxelMap(const VoxelMapConfig& config) : config_(config), revision_(NextRevision()) {}

VoxelMap::Key VoxelMap::KeyOf(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d v = p / config_.voxel_m;
  return {static_cast<int32_t>(std::floor(v.x())), static_cast<int32_t>(std::floor(v.y())),
          static_cast<int32_t>(std::floor(v.z()))};
}

size_t VoxelMap::Insert(const std::vector<Eigen::Vector3d>& points_world) {
  const double min_sq = config_.min_point_spacing_m * config_.min_point_spacing_m;
  size_t stored = 0;
  for (const Eigen::Vector3d& p : points_world) {
    const uint32_t v = FindOrAdd(KeyOf(p));
    uint32_t& count = voxels_[v].count;
    if (count >= config_.max_points_per_voxel) continue;
    Eigen::Vector3d* points = PointsOf(v);
    const bool crowded = std::any_of(points, points + count, [&](const Eigen::Vector3d& q) {
      return (q - p).squaredNorm() < min_sq;
    });
    if (crowded) continue;
    ScoresOf(v)[count] = 0;
    points[count++] = p;
    ++stored;
  }
  points_ += stored;
  if (stored > 0) revision_ = NextRevision();
  return stored;
}

namespace {

/// The query's voxel and its 26 neighbours, nearest cells first (faces, edges, corners), so
/// the k-th best distance shrinks early and prunes the rest.
constexpr std::array<std::array<int, 3>, 27> kSearchOrder = {{
    {0, 0, 0},   {1, 0, 0},   {-1, 0, 0}, {0, 1, 0},   {0, -1, 0},  {0, 0, 1},    {0, 0, -1},
    {1, 1, 0},   {1, -1, 0},  {-1, 1, 0}, {-1, -1, 0}, {1, 0, 1},   {1, 0, -1},   {-1, 0, 1},
    {-1, 0, -1}, {0, 1, 1},   {0, 1, -1}, {0, -1, 1},  {0, -1, -1}, {1, 1, 1},    {1, 1, -1},
    {1, -1, 1},  {1, -1, -1}, {-1, 1, 1}, {-1, 1, -1}, {-1, -1, 1}, {-1, -1, -1},
}};

/// kSearchOrder's offsets as indices into a per-axis table {below, own, above}.
constexpr std::array<std::array<size_t, 3>, 27> kSearchSides = [] {
  std::array<std::array<size_t, 3>, 27> sides{};
  for (size_t i = 0; i < sides.size(); ++i) {
    for (size_t a = 0; a < 3; ++a) {
      const int o = kSearchOrder[i][a];
      sides[i][a] = o < 0 ? 0 : (o == 0 ? 1 : 2);
    }
  }
  return sides;
}();

}  // namespace

// A query's cost is memory, not arithmetic: the 27 cells' index slots are hashed to random
// places in a table of megabytes, and probed one after the other each miss waited for the one
// before (perf: a quarter of Nearest's cycles on the slot load alone). So the search first
// starts the loads of the slots of every cell within the distance bound, then probes them as
// before: the misses overlap. The reads and their order are those of a plain search, so the
// result is the same.
size_t VoxelMap::Nearest(const Eigen::Vector3d& query,
                         size_t k,
                         double max_distance_m,
                         std::vector<Eigen::Vector3d>* out) const {
  out->clear();
  k = std::min(k, kMaxNeighbours);
  if (k == 0 || slots_.empty()) return 0;
  double bound_sq = max_distance_m * max_distance_m;  // the k-th best once full
  const NearCells cells = CellsWithin(query, bound_sq);
  // The k best (distance², point), sorted, in a fixed buffer: no allocation per query.
  std::array<std::pair<double, const Eigen::Vector3d*>, kMaxNeighbours + 1> best;
  size_t n = 0;
  for (size_t i = 0; i < cells.size; ++i) {
    if (cells.box_sq[i] >= bound_sq) continue;  // cannot hold a closer point
    const uint32_t v = FindFrom(cells.key[i], cells.home[i]);
    if (v == kNoVoxel) continue;
    const Eigen::Vector3d* points = PointsOf(v);
    for (uint32_t j = 0; j < voxels_[v].count; ++j) {
      const Eigen::Vector3d& p = points[j];
      const double d2 = (p - query).squaredNorm();
      if (d2 >= bound_sq) continue;
      size_t at = n;
      while (at > 0 && best[at - 1].first > d2) {
        best[at] = best[at - 1];
        --at;
      }
      best[at] = {d2, &p};
      if (n < k) ++n;
      if (n == k) bound_sq = best[k - 1].first;
    }
  }
  for (size_t i = 0; i < n; ++i) out->push_back(*best[i].second);
  return n;
}

VoxelMap::NearCells VoxelMap::CellsWithin(const Eigen::Vector3d& query, double bound_sq) const {
  const Key c = KeyOf(query);
  // Per axis, for the cells below, its own and above: the squared gap from the query (a cell's
  // squared distance from the query is the sum of its three offsets' gaps) and the axis's term
  // of the hash (AxisHash: a cell's hash is the exclusive or of its three).
  const std::array<int32_t, 3> own = {c.x, c.y, c.z};
  std::array<std::array<double, 3>, 3> gap_sq{};
  std::array<std::array<uint64_t, 3>, 3> hash{};
  for (size_t a = 0; a < 3; ++a) {
    const double lo = own[a] * config_.voxel_m;
    const double below = std::max(query[static_cast<Eigen::Index>(a)] - lo, 0.0);
    const double above = std::max(lo + config_.voxel_m - query[static_cast<Eigen::Index>(a)], 0.0);
    gap_sq[a] = {below * below, 0.0, above * above};
    for (size_t side = 0; side < 3; ++side) {
      hash[a][side] = AxisHash(a, own[a] + static_cast<int32_t>(side) - 1);
    }
  }
  NearCells cells;
  for (size_t cell = 0; cell < kSearchOrder.size(); ++cell) {
    const std::array<size_t, 3>& side = kSearchSides[cell];
    const double box_sq = gap_sq[0][side[0]] + gap_sq[1][side[1]] + gap_sq[2][side[2]];
    if (box_sq >= bound_sq) continue;
    const std::array<int, 3>& o = kSearchOrder[cell];
    const size_t i = cells.size++;
    cells.key[i] = {c.x + o[0], c.y + o[1], c.z + o[2]};
    cells.box_sq[i] = box_sq;
    cells.home[i] = HomeOf(hash[0][side[0]] ^ hash[1][side[1]] ^ hash[2][side[2]]);
    __builtin_prefetch(&slots_[cells.home[i]]);
  }
  return cells;
}

std::vector<Eigen::Vector3d> VoxelMap::Points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points_);
  for (uint32_t v = 0; v < voxels_.size(); ++v) {
    const Eigen::Vector3d* points = PointsOf(v);
    out.insert(out.end(), points, points + voxels_[v].count);
  }
  return out;
}

size_t VoxelMap::RemoveFar(const Eigen::Vector3d& center_world) {
  const double r2 = config_.radius_m * config_.radius_m;
  size_t removed = 0;
  // Compacts voxels and their points in place, keeping the survivors' order, then rebuilds
  // the index.
  uint32_t kept = 0;
  for (uint32_t v = 0; v < voxels_.size(); ++v) {
    const Voxel& voxel = voxels_[v];
    const Eigen::Vector3d centre =
        (Eigen::Vector3d(voxel.key.x, voxel.key.y, voxel.key.z) + Eigen::Vector3d::Constant(0.5)) *
        config_.voxel_m;
    if ((centre - center_world).squaredNorm() > r2) {
      removed += voxel.count;
      continue;
    }
    if (kept != v) {
      const Eigen::Vector3d* from = PointsOf(v);
      std::copy(from, from + voxel.count, PointsOf(kept));  // kept < v: another voxel's slots
      const int8_t* from_scores = ScoresOf(v);
      std::copy(from_scores, from_scores + voxel.count, ScoresOf(kept));
      voxels_[kept] = voxel;
    }
    ++kept;
  }
  if (kept == voxels_.size()) return 0;
  voxels_.resize(kept);
  pool_.resize((kept + kChunkVoxels - 1) / kChunkVoxels);
  scores_.resize(pool_.size());
  Reindex(slots_.size());
  points_ -= removed;
  revision_ = NextRevision();
  return removed;
}

void VoxelMap::Removed(size_t points) {
  points_ -= points;
  revision_ = NextRevision();
}

// The classic spatial hash (Teschner et al., 2003): the exclusive or of one term per axis.
uint64_t VoxelMap::AxisHash(size_t axis, int32_t cell) {
  constexpr std::array<uint64_t, 3> kPrimes = {73856093u, 19349669u, 83492791u};
  return uint64_t{static_cast<uint32_t>(cell)} * kPrimes[axis];
}

// Fibonacci hashing: the top bits of the product index the power-of-two table.
size_t VoxelMap::HomeOf(uint64_t hash) const {
  return static_cast<size_t>((hash * 0x9E3779B97F4A7C15ull) >> (64 - slot_bits_));
}

size_t VoxelMap::Home(const Key& key) const {
  return HomeOf(AxisHash(0, key.x) ^ AxisHash(1, key.y) ^ AxisHash(2, key.z));
}

uint32_t VoxelMap::FindFrom(const Key& key, size_t home) const {
  const size_t mask = slots_.size() - 1;
  for (size_t s = home;; s = (s + 1) & mask) {
    const Slot& slot = slots_[s];
    if (slot.voxel == kNoVoxel || slot.key == key) return slot.voxel;
  }
}

uint32_t VoxelMap::FindOrAdd(const Key& key) {
  if (2 * (voxels_.size() + 1) > slots_.size()) Reindex(std::max<size_t>(64, 2 * slots_.size()));
  const size_t mask = slots_.size() - 1;
  size_t s = Home(key);
  for (; slots_[s].voxel != kNoVoxel; s = (s + 1) & mask) {
    if (slots_[s].key == key) return slots_[s].voxel;
  }
  const auto v = static_cast<uint32_t>(voxels_.size());
  slots_[s] = {key, v};
  voxels_.push_back({key, 0});
  if (v / kChunkVoxels >= pool_.size()) {
    pool_.emplace_back(size_t{kChunkVoxels} * config_.max_points_per_voxel);
    scores_.emplace_back(size_t{kChunkVoxels} * config_.max_points_per_voxel, int8_t{0});
  }
  return v;
}

void VoxelMap::Reindex(size_t slot_count) {
  slot_bits_ = std::countr_zero(slot_count);  // slot_count is a power of two
  slots_.assign(slot_count, {});
  const size_t mask = slot_count - 1;
  for (uint32_t v = 0; v < voxels_.size(); ++v) {
    size_t s = Home(voxels_[v].key);
    while (slots_[s].voxel != kNoVoxel) s = (s + 1) & mask;
    slots_[s] = {voxels_[v].key, v};
  }
}

}  // namespace swlio::estimator

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
    uint32_t& count = counts_[v];
    if (count >= config_.max_points_per_voxel) continue;
    Eigen::Vector3d* points = pool_.data() + Begin(v);
    const bool crowded = std::any_of(points, points + count, [&](const Eigen::Vector3d& q) {
      return (q - p).squaredNorm() < min_sq;
    });
    if (crowded) continue;
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

namespace {

/// The k best (distance², point) so far, sorted, in a fixed buffer: no allocation per query.
class KBest {
 public:
  KBest(size_t k, double bound_sq) : k_(k), bound_sq_(bound_sq) {}
  /// Squared distance a point must beat: the search's bound, then the k-th best once full.
  double bound_sq() const { return bound_sq_; }
  void Offer(const Eigen::Vector3d* points, uint32_t count, const Eigen::Vector3d& query) {
    for (uint32_t j = 0; j < count; ++j) {
      const Eigen::Vector3d& p = points[j];
      const double d2 = (p - query).squaredNorm();
      if (d2 >= bound_sq_) continue;
      size_t at = n_;
      while (at > 0 && best_[at - 1].first > d2) {
        best_[at] = best_[at - 1];
        --at;
      }
      best_[at] = {d2, &p};
      if (n_ < k_) ++n_;
      if (n_ == k_) bound_sq_ = best_[k_ - 1].first;
    }
  }
  size_t CopyTo(std::vector<Eigen::Vector3d>* out) const {
    for (size_t i = 0; i < n_; ++i) out->push_back(*best_[i].second);
    return n_;
  }

 private:
  std::array<std::pair<double, const Eigen::Vector3d*>, VoxelMap::kMaxNeighbours + 1> best_;
  size_t n_ = 0;
  size_t k_;
  double bound_sq_;
};

}  // namespace

// A query's cost is memory, not arithmetic: the 27 cells' index slots are hashed to random
// places in a table of megabytes, and each miss waited for the one before (perf: a quarter of
// Nearest's cycles on the slot load alone). The query's own cell is searched first, as it
// always was; when it holds k points, only the cells nearer than its k-th best are listed
// after it, and their slot loads are started together: the misses overlap, and the cells
// that cannot hold a closer point cost no memory traffic (before, all 27 slots were loaded). The
// cells read and their order are those of a plain search in kSearchOrder (a skipped cell's box
// distance is at least the bound, which only shrinks), so the result is the same. Measured no
// faster than starting all 27 (docs/notes/2026-12-03-per-sweep-5ms.md): the own cell's misses
// are now waited for first.
size_t VoxelMap::Nearest(const Eigen::Vector3d& query,
                         size_t k,
                         double max_distance_m,
                         std::vector<Eigen::Vector3d>* out) const {
  out->clear();
  k = std::min(k, kMaxNeighbours);
  if (k == 0 || slots_.empty()) return 0;
  KBest best(k, max_distance_m * max_distance_m);
  const Key own = KeyOf(query);
  if (best.bound_sq() > 0.0) {  // the own cell's box distance is 0
    const uint32_t v = FindFrom(own, Home(own));
    if (v != kNoVoxel) best.Offer(pool_.data() + Begin(v), counts_[v], query);
  }
  const NearCells cells = CellsWithin(query, own, best.bound_sq());
  for (size_t i = 0; i < cells.size; ++i) {
    if (cells.box_sq[i] >= best.bound_sq()) continue;  // cannot hold a closer point
    const uint32_t v = FindFrom(cells.key[i], cells.home[i]);
    if (v != kNoVoxel) best.Offer(pool_.data() + Begin(v), counts_[v], query);
  }
  return best.CopyTo(out);
}

VoxelMap::NearCells VoxelMap::CellsWithin(const Eigen::Vector3d& query,
                                          const Key& c,
                                          double bound_sq) const {
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
  for (size_t cell = 1; cell < kSearchOrder.size(); ++cell) {  // 0, the own cell: searched
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
  for (uint32_t v = 0; v < keys_.size(); ++v) {
    const Eigen::Vector3d* points = pool_.data() + Begin(v);
    out.insert(out.end(), points, points + counts_[v]);
  }
  return out;
}

size_t VoxelMap::RemoveFar(const Eigen::Vector3d& center_world) {
  const double r2 = config_.radius_m * config_.radius_m;
  size_t removed = 0;
  // Compacts voxels and their points in place, keeping the survivors' order, then rebuilds
  // the index.
  uint32_t kept = 0;
  for (uint32_t v = 0; v < keys_.size(); ++v) {
    const Key key = keys_[v];
    const uint32_t count = counts_[v];
    const Eigen::Vector3d centre =
        (Eigen::Vector3d(key.x, key.y, key.z) + Eigen::Vector3d::Constant(0.5)) * config_.voxel_m;
    if ((centre - center_world).squaredNorm() > r2) {
      removed += count;
      continue;
    }
    if (kept != v) {
      const Eigen::Vector3d* from = pool_.data() + Begin(v);
      std::copy(from, from + count,
                pool_.data() + Begin(kept));  // kept < v: the target starts first
      keys_[kept] = key;
      counts_[kept] = count;
    }
    ++kept;
  }
  if (kept == keys_.size()) return 0;
  keys_.resize(kept);
  counts_.resize(kept);
  pool_.resize(Begin(kept));
  Reindex(slots_.size());
  points_ -= removed;
  revision_ = NextRevision();
  return removed;
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
  if (2 * (keys_.size() + 1) > slots_.size()) Reindex(std::max<size_t>(64, 2 * slots_.size()));
  const size_t mask = slots_.size() - 1;
  size_t s = Home(key);
  for (; slots_[s].voxel != kNoVoxel; s = (s + 1) & mask) {
    if (slots_[s].key == key) return slots_[s].voxel;
  }
  const auto v = static_cast<uint32_t>(keys_.size());
  slots_[s] = {key, v};
  keys_.push_back(key);
  counts_.push_back(0);
  pool_.resize(Begin(v + 1));
  return v;
}

void VoxelMap::Reindex(size_t slot_count) {
  slot_bits_ = std::countr_zero(slot_count);  // slot_count is a power of two
  slots_.assign(slot_count, {});
  const size_t mask = slot_count - 1;
  for (uint32_t v = 0; v < keys_.size(); ++v) {
    size_t s = Home(keys_[v]);
    while (slots_[s].voxel != kNoVoxel) s = (s + 1) & mask;
    slots_[s] = {keys_[v], v};
  }
}

}  // namespace swlio::estimator

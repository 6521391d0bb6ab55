#include "swlio/estimator/frontend/feature_extractor.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

namespace swlio::estimator {
namespace {

constexpr uint8_t kNoWindow = 1;    ///< too near a ring end or a gap: no smoothness
constexpr uint8_t kUnreliable = 2;  ///< occluded or beam-parallel
constexpr uint8_t kPicked = 4;      ///< selected, or a suppressed neighbour of a selection
constexpr uint8_t kEdge = 8;

FeaturePoint ToFeature(const SegmentedPoint& p, float curvature) {
  return {p.xyz_m, p.dt_ns, curvature, p.source_index, p.ring};
}

}  // namespace

ConfigIssues FeatureConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange<int64_t>(issues, "half_window", half_window, 1, 20);
  CheckInRange<int64_t>(issues, "sectors_per_ring", sectors_per_ring, 1, 64);
  CheckInRange(issues, "edge_threshold_m2", edge_threshold_m2, 1e-6, 100.0);
  CheckInRange(issues, "planar_threshold_m2", planar_threshold_m2, 1e-6, 100.0);
  CheckInRange<int64_t>(issues, "max_sharp_edges_per_sector", max_sharp_edges_per_sector, 0, 1000);
  CheckInRange<int64_t>(issues, "max_edges_per_sector", max_edges_per_sector,
                        max_sharp_edges_per_sector, 10000);
  CheckInRange<int64_t>(issues, "max_flat_planes_per_sector", max_flat_planes_per_sector, 0, 1000);
  CheckInRange(issues, "occlusion_jump_m", occlusion_jump_m, 0.01, 10.0);
  CheckInRange(issues, "parallel_beam_ratio", parallel_beam_ratio, 1e-4, 1.0);
  CheckInRange(issues, "mixed_pixel_tolerance_m", mixed_pixel_tolerance_m, 0.0, 10.0);
  CheckInRange<int64_t>(issues, "max_neighbour_column_gap", max_neighbour_column_gap, 1, 1000);
  return issues;
}

void FeatureSet::Clear() {
  edges_sharp.clear();
  edges.clear();
  planes_flat.clear();
  planes.clear();
  occluded = 0;
  parallel = 0;
  mixed = 0;
}

void FeatureExtractor::Extract(const SegmentationResult& s, FeatureSet* out) {
  out->Clear();
  const size_t n = s.points.size();
  curvature_.assign(n, 0.0f);
  flags_.assign(n, 0);
  order_.resize(n);
  const auto w = static_cast<size_t>(config_.half_window);
  const auto sectors = static_cast<size_t>(config_.sectors_per_ring);
  for (size_t r = 0; r + 1 < s.ring_begin.size(); ++r) {
    const size_t begin = s.ring_begin[r];
    const size_t end = s.ring_begin[r + 1];
    ComputeSmoothness(s, begin, end);
    RejectUnreliable(s, begin, end, out);
    ring_begin_ = begin;
    ring_end_ = end;
    if (end - begin > 2 * w + sectors) {
      const size_t span = end - begin - 2 * w;
      for (size_t k = 0; k < sectors; ++k) {
        SelectSector(s, begin + w + span * k / sectors, begin + w + span * (k + 1) / sectors, out);
      }
    }
    // Planar set: every smooth point not taken as an edge, and every reliable ground point.
    for (size_t i = begin; i < end; ++i) {
      const uint8_t f = flags_[i];
      if ((f & (kEdge | kUnreliable)) != 0) continue;
      const bool smooth = (f & kNoWindow) == 0 && curvature_[i] < config_.planar_threshold_m2;
      if (smooth || s.points[i].label == kLabelGround) {
        out->planes.push_back(ToFeature(s.points[i], curvature_[i]));
      }
    }
  }
}

// Smoothness along the ring (LeGO-LOAM's range form of LOAM's c):
//   c_i = (Σ_{j=i−W..i+W, j≠i} r_j − 2W·r_i)².
// Windows that reach past the ring's ends or across a wide column gap get no value.
void FeatureExtractor::ComputeSmoothness(const SegmentationResult& s, size_t begin, size_t end) {
  const auto w = static_cast<size_t>(config_.half_window);
  const auto max_span = 2 * config_.max_neighbour_column_gap;
  for (size_t i = begin; i < end; ++i) {
    if (i < begin + w || i + w >= end ||
        s.points[i + w].column - s.points[i - w].column > max_span) {
      flags_[i] |= kNoWindow;
      continue;
    }
    float sum = 0.0f;
    for (size_t j = i - w; j <= i + w; ++j) sum += s.points[j].range_m;
    const float diff = sum - static_cast<float>(2 * w + 1) * s.points[i].range_m;
    curvature_[i] = diff * diff;
  }
}

// A point at a jump against the line through the next two points inward on its ring, where the
// three are evenly spaced in column within the neighbourhood's gap (else the line says nothing).
bool FeatureExtractor::OffItsSurface(const SegmentationResult& s,
                                     size_t edge,
                                     size_t inner,
                                     size_t inner2) const {
  if (config_.mixed_pixel_tolerance_m <= 0.0) return false;
  const SegmentedPoint& e = s.points[edge];
  const SegmentedPoint& p1 = s.points[inner];
  const SegmentedPoint& p2 = s.points[inner2];
  const int step = e.column - p1.column;
  if (step != p1.column - p2.column || std::abs(step) > config_.max_neighbour_column_gap)
    return false;
  const float extrapolated = 2.0f * p1.range_m - p2.range_m;
  return std::abs(e.range_m - extrapolated) > static_cast<float>(config_.mixed_pixel_tolerance_m);
}

// LOAM §V-A: at a range jump between ring neighbours, the W points on the far side lie next to
// an occluding edge and would move with the viewpoint; a point whose range steps away on both
// sides lies on a surface nearly parallel to the beam. Both are unreliable.
void FeatureExtractor::RejectUnreliable(const SegmentationResult& s,
                                        size_t begin,
                                        size_t end,
                                        FeatureSet* out) {
  const auto w = static_cast<size_t>(config_.half_window);
  const auto jump = static_cast<float>(config_.occlusion_jump_m);
  const auto ratio = static_cast<float>(config_.parallel_beam_ratio);
  auto mark = [&](size_t from, size_t to) {  // [from, to)
    for (size_t j = from; j < to; ++j) {
      out->occluded += (flags_[j] & kUnreliable) == 0;
      flags_[j] |= kUnreliable;
    }
  };
  // The near side's edge point, where it lies off its surface's line: a mixed pixel.
  auto mark_mixed = [&](size_t edge, size_t inner, size_t inner2) {
    if (!OffItsSurface(s, edge, inner, inner2)) return;
    out->mixed += (flags_[edge] & kUnreliable) == 0;
    flags_[edge] |= kUnreliable;
  };
  for (size_t i = begin; i + 1 < end; ++i) {
    const SegmentedPoint& a = s.points[i];
    const SegmentedPoint& b = s.points[i + 1];
    if (b.column - a.column > config_.max_neighbour_column_gap) continue;
    if (a.range_m - b.range_m > jump) {
      mark(i >= begin + w ? i - w : begin, i + 1);
      if (i + 3 < end) mark_mixed(i + 1, i + 2, i + 3);
    }
    if (b.range_m - a.range_m > jump) {
      mark(i + 1, std::min(end, i + 2 + w));
      if (i >= begin + 2) mark_mixed(i, i - 1, i - 2);
    }
  }
  for (size_t i = begin + 1; i + 1 < end; ++i) {
    const float r = s.points[i].range_m;
    if (std::abs(s.points[i - 1].range_m - r) > ratio * r &&
        std::abs(s.points[i + 1].range_m - r) > ratio * r && (flags_[i] & kUnreliable) == 0) {
      flags_[i] |= kUnreliable;
      ++out->parallel;
    }
  }
}

void FeatureExtractor::SelectSector(const SegmentationResult& s,
                                    size_t begin,
                                    size_t end,
                                    FeatureSet* out) {
  // Keys: the smoothness's IEEE bits (c ≥ 0, so they order as integers) above the index, so
  // all differ. The edges are taken from the largest down and the flats from the smallest up,
  // each loop stopping after a few (20 and 4 of ~170 points): a heap yields the keys in the
  // same order as the sorted sector did, one at a time, for O(n) to build it instead of a
  // sort's O(n log n) (perf: the sort had been ~3.5 % of swlio-run's cycles).
  const auto first = order_.begin() + static_cast<std::ptrdiff_t>(begin);
  const auto last = order_.begin() + static_cast<std::ptrdiff_t>(end);
  for (size_t i = begin; i < end; ++i) {
    order_[i] = (uint64_t{std::bit_cast<uint32_t>(curvature_[i])} << 32) | i;
  }
  constexpr uint8_t kBlocked = kNoWindow | kUnreliable | kPicked;
  std::make_heap(first, last);  // largest on top
  int64_t edges = 0;
  for (auto top = last; top != first && edges < config_.max_edges_per_sector;) {
    std::pop_heap(first, top--);
    const auto i = static_cast<uint32_t>(*top);
    if (curvature_[i] <= config_.edge_threshold_m2) break;
    if ((flags_[i] & kBlocked) != 0 || s.points[i].label == kLabelGround) continue;
    const FeaturePoint f = ToFeature(s.points[i], curvature_[i]);
    if (edges++ < config_.max_sharp_edges_per_sector) out->edges_sharp.push_back(f);
    out->edges.push_back(f);
    flags_[i] |= kPicked | kEdge;
    Suppress(s, i);
  }
  std::make_heap(first, last, std::greater<>{});  // smallest on top
  int64_t flats = 0;
  for (auto top = last; top != first && flats < config_.max_flat_planes_per_sector;) {
    std::pop_heap(first, top--, std::greater<>{});
    const auto i = static_cast<uint32_t>(*top);
    if (curvature_[i] >= config_.planar_threshold_m2) break;
    if ((flags_[i] & kBlocked) != 0) continue;
    out->planes_flat.push_back(ToFeature(s.points[i], curvature_[i]));
    ++flats;
    flags_[i] |= kPicked;
    Suppress(s, i);
  }
}

// Neighbour suppression: the W ring neighbours on each side of a selected point (up to a
// column gap, across sector borders) cannot be selected in turn, which spreads the features.
void FeatureExtractor::Suppress(const SegmentationResult& s, size_t i) {
  const size_t begin = ring_begin_;
  const size_t end = ring_end_;
  const auto w = static_cast<size_t>(config_.half_window);
  for (size_t j = i + 1; j < end && j <= i + w; ++j) {
    if (s.points[j].column - s.points[j - 1].column > config_.max_neighbour_column_gap) break;
    flags_[j] |= kPicked;
  }
  for (size_t j = i; j > begin && j + w > i; --j) {
    if (s.points[j].column - s.points[j - 1].column > config_.max_neighbour_column_gap) break;
    flags_[j - 1] |= kPicked;
  }
}

}  // namespace swlio::estimator

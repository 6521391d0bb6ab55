// Local map (voxel_map.h) against a nanoflann kd-tree, on a simulated substation drive.
//
// Data: the `short` scenario, seed 1, along the south road at 1.2 m/s. Sweeps at 3.0, 3.5, …,
// 22.5 s go through the FrontEnd (segmentation, features, planes at 0.4 m) and are placed in
// the world with their true pose. Sweeps at whole seconds are keyframes (≈ 1.2 m apart): the
// map is made of the first N of them (N = 10 or 20, the benchmark argument). Sweeps at half
// seconds inside the map's span are the probes: the planar points the scan matcher would query
// (k = 5 within 1.5 m, ScanMatcherConfig's defaults) and insert. Both structures hold the same
// input points; the VoxelMap in its default configuration thins them (20 per 1 m voxel, 0.1 m
// spacing), a "keep-all" VoxelMap holds every point so its answers can be compared with the
// exact kd-tree's (counter `same_as_kdtree`).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <nanoflann.hpp>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"
#include "swlio/estimator/frontend/front_end.h"
#include "swlio/estimator/registration/voxel_map.h"

namespace {

using namespace swlio::estimator;  // NOLINT(google-build-using-namespace): bench file only
using Cloud = std::vector<Eigen::Vector3d>;

constexpr size_t kNeighbors = 5;
constexpr double kMaxDistanceM = 1.5;

struct Sweep {
  Cloud planes_world;
  Eigen::Vector3d position_world;
};

struct DriveData {
  std::vector<Sweep> keyframes;  ///< t = 3, 4, …, 22 s
  std::vector<Sweep> probes;     ///< t = 3.5, 4.5, …, 22.5 s
};

const DriveData& Drive() {
  static const DriveData data = [] {
    auto setup = swlio::sim::MakeSimSetup("short", 1, 23.0);
    if (!setup) std::abort();
    swlio::sim::LabelledScanSource source(*setup);
    FrontEnd front_end(FrontEndConfig{});
    FrontEndOutput out;
    swlio::sim::LabelledScan ls;
    DriveData d;
    for (int i = 0; i < 40; ++i) {
      if (!source.Next(&ls, 3.0 + 0.5 * i)) std::abort();
      front_end.Process(ls.scan, &out);
      Sweep s;
      for (const auto& f : out.features.planes) {
        s.planes_world.push_back(ls.T_world_lidar_end * f.xyz_m.cast<double>());
      }
      s.position_world = ls.T_world_lidar_end.translation();
      (i % 2 == 0 ? d.keyframes : d.probes).push_back(std::move(s));
    }
    return d;
  }();
  return data;
}

/// The union of the first `n` keyframes.
Cloud MapPoints(size_t n) {
  Cloud all;
  for (size_t i = 0; i < n; ++i) {
    const Cloud& c = Drive().keyframes[i].planes_world;
    all.insert(all.end(), c.begin(), c.end());
  }
  return all;
}

VoxelMapConfig KeepAllConfig() {
  VoxelMapConfig c;
  c.max_points_per_voxel = 1000;
  c.min_point_spacing_m = 0.0;
  return c;
}

VoxelMap BuildMap(size_t n, const VoxelMapConfig& config) {
  VoxelMap map(config);
  for (size_t i = 0; i < n; ++i) map.Insert(Drive().keyframes[i].planes_world);
  return map;
}

/// Probes inside the span of `n` keyframes.
size_t ProbeCount(size_t n) { return n - 1; }

size_t Keyframes(const benchmark::State& state) { return static_cast<size_t>(state.range(0)); }

// ---- nanoflann ---------------------------------------------------------------------------

struct CloudAdaptor {
  const Cloud* pts;
  size_t kdtree_get_point_count() const { return pts->size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return (*pts)[i][static_cast<int>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;
  }
};
using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>,
                                        CloudAdaptor,
                                        3,
                                        uint32_t>;

/// Up to k nearest within `max_distance_m` (the bound pre-set as the worst distance), sorted.
size_t KdNearest(const KdTree& tree, const Eigen::Vector3d& q, uint32_t* idx, double* d2) {
  nanoflann::KNNResultSet<double, uint32_t> result(kNeighbors);
  result.init(idx, d2);
  d2[kNeighbors - 1] = kMaxDistanceM * kMaxDistanceM;
  tree.findNeighbors(result, q.data(), nanoflann::SearchParams());
  return result.size();
}

// ---- VoxelMap ------------------------------------------------------------------------------

void BM_MapBuild(benchmark::State& state) {
  const size_t n = Keyframes(state);
  size_t points = 0;
  size_t offered = 0;
  for (size_t i = 0; i < n; ++i) offered += Drive().keyframes[i].planes_world.size();
  for (auto _ : state) {
    VoxelMap map = BuildMap(n, VoxelMapConfig{});
    points = map.size();
    benchmark::DoNotOptimize(points);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(offered));
  state.counters["offered"] = static_cast<double>(offered);
  state.counters["stored"] = static_cast<double>(points);
}
BENCHMARK(BM_MapBuild)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

// One probe sweep inserted into the map of n keyframes, then RemoveFar around its position.
void BM_MapInsertRemoveFar(benchmark::State& state) {
  const size_t n = Keyframes(state);
  VoxelMap base = BuildMap(n, VoxelMapConfig{});
  base.RemoveFar(Drive().keyframes[n - 1].position_world);  // as after the last keyframe
  size_t j = 0, offered = 0, inserted = 0, removed = 0;
  for (auto _ : state) {
    state.PauseTiming();
    VoxelMap map = base;
    const Sweep& s = Drive().probes[j++ % ProbeCount(n)];
    state.ResumeTiming();
    inserted += map.Insert(s.planes_world);
    removed += map.RemoveFar(s.position_world);
    offered += s.planes_world.size();
    state.PauseTiming();
    { VoxelMap discard = std::move(map); }  // the free is not timed
    state.ResumeTiming();
  }
  state.SetItemsProcessed(static_cast<int64_t>(offered));
  const double it = static_cast<double>(state.iterations());
  state.counters["offered"] = static_cast<double>(offered) / it;
  state.counters["inserted"] = static_cast<double>(inserted) / it;
  state.counters["removed"] = static_cast<double>(removed) / it;
  state.counters["map_voxels"] = static_cast<double>(base.voxels());
}
BENCHMARK(BM_MapInsertRemoveFar)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

// RemoveFar alone, when nothing is far (visits every voxel): its floor per sweep.
void BM_MapRemoveFarNoop(benchmark::State& state) {
  VoxelMap map = BuildMap(Keyframes(state), VoxelMapConfig{});
  map.RemoveFar(Drive().keyframes[0].position_world);
  for (auto _ : state) benchmark::DoNotOptimize(map.RemoveFar(Drive().keyframes[0].position_world));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(map.voxels()));
  state.counters["map_voxels"] = static_cast<double>(map.voxels());
}
BENCHMARK(BM_MapRemoveFarNoop)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

// k = 5 within 1.5 m for every planar point of one probe sweep (cycled).
void MapNearest(benchmark::State& state, const VoxelMapConfig& config) {
  const size_t n = Keyframes(state);
  const VoxelMap map = BuildMap(n, config);
  Cloud nn;
  size_t j = 0, queries = 0, full = 0;
  for (auto _ : state) {
    for (const auto& q : Drive().probes[j++ % ProbeCount(n)].planes_world) {
      full += map.Nearest(q, kNeighbors, kMaxDistanceM, &nn) == kNeighbors ? 1 : 0;
      ++queries;
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(queries));
  state.counters["queries"] =
      static_cast<double>(queries) / static_cast<double>(state.iterations());
  state.counters["found_k"] = static_cast<double>(full) / static_cast<double>(queries);
  state.counters["map_points"] = static_cast<double>(map.size());
}

/// Fraction of probe queries where `map` returns exactly the kd-tree's neighbours (distances).
double SameAsKdTree(size_t n, const VoxelMap& map) {
  const Cloud pts = MapPoints(n);
  const CloudAdaptor adaptor{&pts};
  const KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  Cloud nn;
  uint32_t idx[kNeighbors];
  double d2[kNeighbors];
  size_t same = 0, total = 0;
  for (size_t j = 0; j < ProbeCount(n); ++j) {
    for (const auto& q : Drive().probes[j].planes_world) {
      const size_t m = KdNearest(tree, q, idx, d2);
      bool equal = map.Nearest(q, kNeighbors, kMaxDistanceM, &nn) == m;
      for (size_t i = 0; equal && i < m; ++i) {
        equal = std::abs((nn[i] - q).squaredNorm() - d2[i]) <= 1e-9;
      }
      same += equal ? 1 : 0;
      ++total;
    }
  }
  return static_cast<double>(same) / static_cast<double>(total);
}

void BM_MapNearest(benchmark::State& state) { MapNearest(state, VoxelMapConfig{}); }
BENCHMARK(BM_MapNearest)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

void BM_MapNearestKeepAll(benchmark::State& state) {
  MapNearest(state, KeepAllConfig());
  const size_t n = Keyframes(state);
  const VoxelMap map = BuildMap(n, KeepAllConfig());
  if (map.size() != MapPoints(n).size()) state.SkipWithError("keep-all map dropped points");
  state.counters["same_as_kdtree"] = SameAsKdTree(n, map);
}
BENCHMARK(BM_MapNearestKeepAll)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

// ---- kd-tree -----------------------------------------------------------------------------

void BM_KdTreeBuild(benchmark::State& state) {
  const Cloud pts = MapPoints(Keyframes(state));
  const CloudAdaptor adaptor{&pts};
  for (auto _ : state) {
    KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    benchmark::DoNotOptimize(&tree);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(pts.size()));
  state.counters["points"] = static_cast<double>(pts.size());
}
BENCHMARK(BM_KdTreeBuild)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

void BM_KdTreeNearest(benchmark::State& state) {
  const size_t n = Keyframes(state);
  const Cloud pts = MapPoints(n);
  const CloudAdaptor adaptor{&pts};
  const KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  uint32_t idx[kNeighbors];
  double d2[kNeighbors];
  size_t j = 0, queries = 0, full = 0;
  for (auto _ : state) {
    for (const auto& q : Drive().probes[j++ % ProbeCount(n)].planes_world) {
      full += KdNearest(tree, q, idx, d2) == kNeighbors ? 1 : 0;
      ++queries;
    }
    benchmark::DoNotOptimize(d2);
  }
  state.SetItemsProcessed(static_cast<int64_t>(queries));
  state.counters["queries"] =
      static_cast<double>(queries) / static_cast<double>(state.iterations());
  state.counters["found_k"] = static_cast<double>(full) / static_cast<double>(queries);
  state.counters["map_points"] = static_cast<double>(pts.size());
}
BENCHMARK(BM_KdTreeNearest)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace

// Front end per simulated RS16 sweep (~17,000 points): segmentation (paper §4.1), LOAM
// features, and the voxel filter of eqs. (14)–(16). Input: the `short` scenario, seed 1, the
// sweep at 0.5 s (standing still), built from the simulator's returns.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cstdlib>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"
#include "swlio/estimator/frontend/feature_extractor.h"
#include "swlio/estimator/frontend/segmentation.h"
#include "swlio/estimator/frontend/voxel_filter.h"

namespace {

using namespace swlio::estimator;  // NOLINT(google-build-using-namespace): bench file only

const swlio::Scan& SimulatedSweep() {
  static const swlio::Scan scan = [] {
    auto setup = swlio::sim::MakeSimSetup("short", 1, 1.0);
    if (!setup) std::abort();
    swlio::sim::LabelledScanSource source(*setup);
    swlio::sim::LabelledScan ls;
    if (!source.Next(&ls, 0.5)) std::abort();
    return ls.scan;
  }();
  return scan;
}

void BM_RangeImage(benchmark::State& state) {
  const swlio::Scan& scan = SimulatedSweep();
  RangeImage image(RangeImageConfig{});
  for (auto _ : state) benchmark::DoNotOptimize(image.Build(scan.points));
}
BENCHMARK(BM_RangeImage)->Unit(benchmark::kMicrosecond);

void BM_Segmentation(benchmark::State& state) {
  const swlio::Scan& scan = SimulatedSweep();
  Segmenter segmenter(SegmentationConfig{});
  SegmentationResult result;
  for (auto _ : state) {
    segmenter.Segment(scan, &result);
    benchmark::DoNotOptimize(result.points.data());
  }
  state.counters["points"] = static_cast<double>(scan.points.size());
  state.counters["segmented"] = static_cast<double>(result.points.size());
}
BENCHMARK(BM_Segmentation)->Unit(benchmark::kMicrosecond);

void BM_Features(benchmark::State& state) {
  Segmenter segmenter(SegmentationConfig{});
  SegmentationResult segmented;
  segmenter.Segment(SimulatedSweep(), &segmented);
  FeatureExtractor extractor(FeatureConfig{});
  FeatureSet features;
  for (auto _ : state) {
    extractor.Extract(segmented, &features);
    benchmark::DoNotOptimize(features.planes.data());
  }
  state.counters["edges"] = static_cast<double>(features.edges.size());
  state.counters["planes"] = static_cast<double>(features.planes.size());
}
BENCHMARK(BM_Features)->Unit(benchmark::kMicrosecond);

std::vector<Eigen::Vector3f> SweepPositions() {
  std::vector<Eigen::Vector3f> positions;
  for (const auto& p : SimulatedSweep().points) positions.push_back(p.xyz_m);
  return positions;
}

void BM_VoxelFixed(benchmark::State& state) {
  const auto positions = SweepPositions();
  const double cell_m = static_cast<double>(state.range(0)) / 100.0;
  VoxelFilter filter;
  std::vector<uint32_t> kept;
  for (auto _ : state) {
    filter.FilterFixed(positions, cell_m, &kept);
    benchmark::DoNotOptimize(kept.data());
  }
  state.counters["kept"] = static_cast<double>(kept.size());
}
BENCHMARK(BM_VoxelFixed)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);

void BM_VoxelAdaptive(benchmark::State& state) {
  const auto positions = SweepPositions();
  VoxelFilterConfig config;
  config.points_per_voxel = static_cast<double>(state.range(0));
  VoxelFilter filter;
  std::vector<uint32_t> kept;
  VoxelFilterResult r;
  for (auto _ : state) {
    r = filter.FilterAdaptive(positions, config, &kept);
    benchmark::DoNotOptimize(kept.data());
  }
  state.counters["kept"] = static_cast<double>(kept.size());
  state.counters["cell_m"] = r.cell_m;
  Eigen::AlignedBox3f box;
  for (const auto& p : positions) box.extend(p);
  state.counters["unclamped_cell_m"] =
      AdaptiveCellSize(box.sizes(), positions.size(), config.points_per_voxel, config.min_cell_m);
  state.counters["extent_x_m"] = box.sizes().x();
  state.counters["extent_y_m"] = box.sizes().y();
  state.counters["extent_z_m"] = box.sizes().z();
}
BENCHMARK(BM_VoxelAdaptive)->Arg(8)->Unit(benchmark::kMicrosecond);

// Segmentation + features + planes at 0.4 m and edges at 0.2 m (the default map voxels).
void BM_FrontEndWithoutDeskew(benchmark::State& state) {
  const swlio::Scan& scan = SimulatedSweep();
  Segmenter segmenter(SegmentationConfig{});
  SegmentationResult segmented;
  FeatureExtractor extractor(FeatureConfig{});
  FeatureSet features;
  VoxelFilter filter;
  for (auto _ : state) {
    segmenter.Segment(scan, &segmented);
    extractor.Extract(segmented, &features);
    filter.Apply(&features.planes, 0.4);
    filter.Apply(&features.edges, 0.2);
    benchmark::DoNotOptimize(features.planes.data());
  }
  state.counters["planes"] = static_cast<double>(features.planes.size());
  state.counters["edges"] = static_cast<double>(features.edges.size());
}
BENCHMARK(BM_FrontEndWithoutDeskew)->Unit(benchmark::kMicrosecond);

// The same over 30 consecutive sweeps of the `aggressive` drive while it moves (3–6 s),
// cycled: the mean over varied scenes.
void BM_FrontEndDriveSweeps(benchmark::State& state) {
  static const std::vector<swlio::Scan> sweeps = [] {
    auto setup = swlio::sim::MakeSimSetup("aggressive", 1, 6.0);
    if (!setup) std::abort();
    swlio::sim::LabelledScanSource source(*setup);
    swlio::sim::LabelledScan ls;
    std::vector<swlio::Scan> out;
    while (out.size() < 30 && source.Next(&ls, 3.0)) out.push_back(ls.scan);
    return out;
  }();
  Segmenter segmenter(SegmentationConfig{});
  SegmentationResult segmented;
  FeatureExtractor extractor(FeatureConfig{});
  FeatureSet features;
  VoxelFilter filter;
  size_t k = 0;
  for (auto _ : state) {
    segmenter.Segment(sweeps[k++ % sweeps.size()], &segmented);
    extractor.Extract(segmented, &features);
    filter.Apply(&features.planes, 0.4);
    filter.Apply(&features.edges, 0.2);
    benchmark::DoNotOptimize(features.planes.data());
  }
  state.counters["sweeps"] = static_cast<double>(sweeps.size());
}
BENCHMARK(BM_FrontEndDriveSweeps)->Unit(benchmark::kMicrosecond);

}  // namespace

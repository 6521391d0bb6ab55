// The front end allocates nothing once its buffers have grown to a sweep's size: a second pass
// over the same sweep makes no heap allocation. Counted with a replaced global operator new
// (this test binary only).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "labelled_scan.h"
#include "sim_setup.h"
#include "swlio/estimator/feature_extractor.h"
#include "swlio/estimator/segmentation.h"
#include "swlio/estimator/voxel_filter.h"

namespace {
std::atomic<int64_t> g_allocations{0};
}  // namespace

[[gnu::noinline]] void* operator new(size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// Not inlined: GCC would otherwise pair an inlined free() with `new` and warn
// (-Wmismatched-new-delete) although both sides are the replacements here.
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, size_t) noexcept { std::free(p); }

namespace swlio::estimator {
namespace {

TEST(FrontEnd, SecondPassOverASweepDoesNotAllocate) {
  auto setup = sim::MakeSimSetup("short", 1, 1.0);
  ASSERT_TRUE(setup.has_value());
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  ASSERT_TRUE(source.Next(&ls, 0.5));

  Segmenter segmenter(SegmentationConfig{});
  SegmentationResult segmented;
  FeatureExtractor extractor(FeatureConfig{});
  FeatureSet features;
  VoxelFilter filter;
  VoxelFilterConfig adaptive;
  auto run = [&] {
    segmenter.Segment(ls.scan, &segmented);
    extractor.Extract(segmented, &features);
    filter.Apply(&features.planes, 0.4);
    filter.Apply(&features.edges, adaptive);
  };
  run();
  const size_t planes = features.planes.size();
  const int64_t before = g_allocations.load();
  ASSERT_GT(before, 0);  // the counter sees the first pass grow its buffers
  run();
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(features.planes.size(), planes);  // and the same result
  EXPECT_GT(planes, 0u);
}

}  // namespace
}  // namespace swlio::estimator

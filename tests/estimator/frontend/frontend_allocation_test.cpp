// The front end allocates nothing once its buffers have grown to a sweep's size: a second pass
// over the same sweep makes no heap allocation. Counted with a replaced global operator new
// (this test binary only).
#include <gtest/gtest.h>

#include <memory>

#include "allocation_counter.h"

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"
#include "swlio/estimator/frontend/deskew.h"
#include "swlio/estimator/frontend/feature_extractor.h"
#include "swlio/estimator/frontend/segmentation.h"
#include "swlio/estimator/frontend/voxel_filter.h"

namespace swlio::estimator {
namespace {

TEST(AllocationCounter, SeesOperatorNew) {  // else the tests below could not fail
  const int64_t before = test::HeapAllocations();
  auto p = std::make_unique<int>(1);
  EXPECT_EQ(test::HeapAllocations() - before, 1);
}

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
  const int64_t before = test::HeapAllocations();
  ASSERT_GT(before, 0);  // the counter sees the first pass grow its buffers
  run();
  EXPECT_EQ(test::HeapAllocations() - before, 0);
  EXPECT_EQ(features.planes.size(), planes);  // and the same result
  EXPECT_GT(planes, 0u);
}

// The window de-skews each sweep into one Scan it keeps: once that has a sweep's capacity, a
// sweep of that size or smaller is de-skewed without allocating.
TEST(DeskewScan, IntoAKeptScanDoesNotAllocate) {
  auto setup = sim::MakeSimSetup("short", 1, 1.0);
  ASSERT_TRUE(setup.has_value());
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  ASSERT_TRUE(source.Next(&ls, 0.5));
  PoseTrack track;
  track.Add(ls.scan.t_start_ns, Eigen::Isometry3d::Identity());
  Eigen::Isometry3d T_end = Eigen::Isometry3d::Identity();
  T_end.translation().x() = 0.15;
  track.Add(ls.scan.t_end_ns, T_end);
  Scan kept;
  DeskewScan(ls.scan, track, Eigen::Isometry3d::Identity(), &kept);
  const int64_t before = test::HeapAllocations();
  const DeskewResult r = DeskewScan(ls.scan, track, Eigen::Isometry3d::Identity(), &kept);
  EXPECT_EQ(test::HeapAllocations() - before, 0);
  EXPECT_EQ(r.points, ls.scan.points.size());
  EXPECT_EQ(r.uncovered, 0u);
}

}  // namespace
}  // namespace swlio::estimator

// The front-end façade: the same as calling its stages by hand, in order.
#include "swlio/estimator/frontend/front_end.h"

#include <gtest/gtest.h>

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"

namespace swlio::estimator {
namespace {

TEST(FrontEnd, EqualsTheStagesInOrder) {
  auto setup = sim::MakeSimSetup("degenerate", 2, 1.0);
  ASSERT_TRUE(setup.has_value());
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  ASSERT_TRUE(source.Next(&ls, 0.5));

  FrontEndConfig config;
  config.edge_voxel_m = 0.0;  // edges through the adaptive cell of eq. (14)
  ASSERT_TRUE(config.Validate().empty());
  FrontEnd front_end(config);
  FrontEndOutput out;
  front_end.Process(ls.scan, &out);

  Segmenter segmenter(config.segmentation);
  SegmentationResult segmented;
  segmenter.Segment(ls.scan, &segmented);
  FeatureExtractor extractor(config.features);
  FeatureSet features;
  extractor.Extract(segmented, &features);
  VoxelFilter filter;
  const size_t planes_before = features.planes.size();
  filter.Apply(&features.planes, config.plane_voxel_m);
  const VoxelFilterResult edges = filter.Apply(&features.edges, config.adaptive);

  EXPECT_EQ(out.segmentation.labels, segmented.labels);
  ASSERT_EQ(out.features.planes.size(), features.planes.size());
  ASSERT_EQ(out.features.edges.size(), features.edges.size());
  for (size_t i = 0; i < features.planes.size(); ++i) {
    EXPECT_EQ(out.features.planes[i].source_index, features.planes[i].source_index);
  }
  EXPECT_EQ(out.plane_filter.input_points, planes_before);
  EXPECT_LT(out.features.planes.size(), planes_before / 2);
  EXPECT_DOUBLE_EQ(out.edge_filter.cell_m, edges.cell_m);
  EXPECT_DOUBLE_EQ(out.plane_filter.cell_m, 0.4);

  FrontEndConfig bad;
  bad.plane_voxel_m = -1.0;
  bad.features.half_window = 0;
  const ConfigIssues issues = bad.Validate();
  ASSERT_EQ(issues.size(), 2u);
  EXPECT_EQ(issues[0].key, "features.half_window");
  EXPECT_EQ(issues[1].key, "plane_voxel_m");
}

}  // namespace
}  // namespace swlio::estimator

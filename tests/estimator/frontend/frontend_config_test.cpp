// Validate() of the front-end config structs.
#include <gtest/gtest.h>

#include "swlio/estimator/frontend/feature_extractor.h"
#include "swlio/estimator/frontend/segmentation.h"
#include "swlio/estimator/frontend/voxel_filter.h"

namespace swlio::estimator {
namespace {

TEST(FrontEndConfigs, DefaultsAreValidAndViolationsAreNamed) {
  EXPECT_TRUE(SegmentationConfig{}.Validate().empty());
  EXPECT_TRUE(FeatureConfig{}.Validate().empty());
  EXPECT_TRUE(VoxelFilterConfig{}.Validate().empty());
  SegmentationConfig s;
  s.image.columns = 0;
  s.cluster_angle_deg = 95.0;
  const ConfigIssues issues = s.Validate();
  ASSERT_EQ(issues.size(), 2u);
  EXPECT_EQ(issues[0].key, "image.columns");
  EXPECT_EQ(issues[1].key, "cluster_angle_deg");
  FeatureConfig f;
  f.max_edges_per_sector = 1;  // fewer than the sharp ones
  ASSERT_EQ(f.Validate().size(), 1u);
  EXPECT_EQ(f.Validate()[0].key, "max_edges_per_sector");
  VoxelFilterConfig v;
  v.min_cell_m = 2.0;
  v.max_cell_m = 1.0;
  ASSERT_EQ(v.Validate().size(), 1u);
  EXPECT_EQ(v.Validate()[0].key, "max_cell_m");
}

}  // namespace
}  // namespace swlio::estimator

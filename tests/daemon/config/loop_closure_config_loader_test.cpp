// estimator.loop_closure: loop closure's options in the YAML configuration.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "swlio/daemon/config/config_loader.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using estimator::LoopClosureConfig;
using ::testing::HasSubstr;

LoadedConfig Load(const std::string& text) {
  return LoadConfigText(text, "test.yaml", "/etc/swlio");
}

void ExpectSame(const LoopClosureConfig& a, const LoopClosureConfig& b) {
  EXPECT_EQ(a.enabled, b.enabled);
  EXPECT_EQ(a.keyframe_distance_m, b.keyframe_distance_m);
  EXPECT_EQ(a.keyframe_angle_rad, b.keyframe_angle_rad);
  EXPECT_EQ(a.search_radius_m, b.search_radius_m);
  EXPECT_EQ(a.min_separation_s, b.min_separation_s);
  EXPECT_EQ(a.attempt_every_nodes, b.attempt_every_nodes);
  EXPECT_EQ(a.submap_half_width, b.submap_half_width);
  EXPECT_EQ(a.inlier_distance_m, b.inlier_distance_m);
  EXPECT_EQ(a.min_fitness, b.min_fitness);
  EXPECT_EQ(a.min_inliers, b.min_inliers);
  EXPECT_EQ(a.min_hessian_eigenvalue, b.min_hessian_eigenvalue);
  EXPECT_EQ(a.max_correction_m, b.max_correction_m);
  EXPECT_EQ(a.max_correction_rad, b.max_correction_rad);
  EXPECT_EQ(a.odometry_sigma_m, b.odometry_sigma_m);
  EXPECT_EQ(a.odometry_sigma_rad, b.odometry_sigma_rad);
  EXPECT_EQ(a.loop_sigma_m, b.loop_sigma_m);
  EXPECT_EQ(a.loop_sigma_rad, b.loop_sigma_rad);
  EXPECT_EQ(a.max_loop_chi2, b.max_loop_chi2);
  EXPECT_EQ(a.loop_kernel, b.loop_kernel);
  EXPECT_EQ(a.max_iterations, b.max_iterations);
  EXPECT_EQ(a.output_max_rate_mps, b.output_max_rate_mps);
  EXPECT_EQ(a.output_max_rate_radps, b.output_max_rate_radps);
}

// The shipped file states every default, so editing one there is editing the right thing.
TEST(LoopClosureConfigLoader, ShippedFileStatesTheDefaults) {
  const LoadedConfig loaded = LoadConfigFile(test::SourceDir() / "config" / "swlio.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  ExpectSame(loaded.config.loop_closure, LoopClosureConfig{});
}

TEST(LoopClosureConfigLoader, ValuesAreStored) {
  const LoadedConfig loaded = Load(R"(config_version: 1
estimator:
  loop_closure:
    enabled: false
    search_radius_m: 15.0
    min_separation_s: 60
    min_inliers: 250
    max_loop_chi2: 0
)");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  const LoopClosureConfig& c = loaded.config.loop_closure;
  EXPECT_FALSE(c.enabled);  // on by default
  EXPECT_EQ(c.search_radius_m, 15.0);
  EXPECT_EQ(c.min_separation_s, 60.0);
  EXPECT_EQ(c.min_inliers, 250);
  EXPECT_EQ(c.max_loop_chi2, 0.0);
}

TEST(LoopClosureConfigLoader, ErrorsNameKeyAndLine) {
  const LoadedConfig loaded = Load(R"(config_version: 1
estimator:
  loop_closure:
    min_fitness: 1.5
    search_radius: 10
)");
  ASSERT_EQ(loaded.errors.size(), 2u) << loaded.ErrorReport();  // in line order
  EXPECT_EQ(loaded.errors[0].key, "estimator.loop_closure.min_fitness");
  EXPECT_EQ(loaded.errors[0].line, 4);
  EXPECT_THAT(loaded.errors[0].reason, HasSubstr("must be in [0, 1], got 1.5"));
  EXPECT_EQ(loaded.errors[1].key, "estimator.loop_closure.search_radius");
  EXPECT_THAT(loaded.errors[1].reason, HasSubstr("did you mean 'search_radius_m'"));
}

}  // namespace
}  // namespace swlio::daemon

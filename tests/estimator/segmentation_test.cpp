// Segmentation (paper §4.1) against the simulator's true surface classes.
#include "swlio/estimator/segmentation.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "labelled_scan.h"
#include "sim_setup.h"

namespace swlio::estimator {
namespace {

using sim::SurfaceClass;

struct Case {
  std::string scenario;
  uint64_t seed;
  double t_min_s;  ///< first sweep at or after this time (the robot moves after 2 s)
};

class GroundTest : public ::testing::TestWithParam<Case> {};

TEST_P(GroundTest, PrecisionAndRecallAgainstSimulatorClasses) {
  const Case& c = GetParam();
  auto setup = sim::MakeSimSetup(c.scenario, c.seed, c.t_min_s + 0.5);
  ASSERT_TRUE(setup.has_value());
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  ASSERT_TRUE(source.Next(&ls, c.t_min_s));
  ASSERT_GT(ls.scan.points.size(), 10000u);

  Segmenter segmenter(SegmentationConfig{});
  SegmentationResult result;
  segmenter.Segment(ls.scan, &result);
  ASSERT_EQ(result.labels.size(), ls.scan.points.size());

  int64_t tp = 0, fp = 0, fn = 0;
  for (size_t i = 0; i < result.labels.size(); ++i) {
    const bool predicted = result.labels[i] == kLabelGround;
    const bool truth = ls.cls[i] == SurfaceClass::kGround;
    tp += predicted && truth;
    fp += predicted && !truth;
    fn += !predicted && truth;
  }

  const double precision = static_cast<double>(tp) / static_cast<double>(tp + fp);
  const double recall = static_cast<double>(tp) / static_cast<double>(tp + fn);
  RecordProperty("precision", std::to_string(precision));
  RecordProperty("recall", std::to_string(recall));
  std::printf(
      "%s seed %llu t %.1f: points %zu ground tp %lld fp %lld fn %lld  P %.4f R %.4f  "
      "clusters %lld outliers %lld collisions %lld\n",
      c.scenario.c_str(), static_cast<unsigned long long>(c.seed), c.t_min_s, ls.scan.points.size(),
      static_cast<long long>(tp), static_cast<long long>(fp), static_cast<long long>(fn), precision,
      recall, static_cast<long long>(result.clusters),
      static_cast<long long>(result.outlier_points),
      static_cast<long long>(result.image.collisions));
  EXPECT_GE(precision, 0.95);
  EXPECT_GE(recall, 0.95);
}

INSTANTIATE_TEST_SUITE_P(Scenarios,
                         GroundTest,
                         ::testing::Values(Case{"short", 1, 0.5},
                                           Case{"loop943", 2, 0.5},
                                           Case{"degenerate", 3, 1.0},
                                           Case{"aggressive", 1, 1.5},
                                           Case{"short", 2, 6.0},
                                           Case{"aggressive", 3, 5.0}),
                         [](const auto& info) {
                           return info.param.scenario + "_seed" + std::to_string(info.param.seed) +
                                  "_t" + std::to_string(static_cast<int>(info.param.t_min_s * 10));
                         });

}  // namespace
}  // namespace swlio::estimator

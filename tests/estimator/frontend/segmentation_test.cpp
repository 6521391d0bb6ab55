// Segmentation (paper §4.1) against the simulator's true surface classes.
#include "swlio/estimator/frontend/segmentation.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <map>
#include <string>

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"

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

// Structure of the output on a real-looking sweep: ring-major column order, labels agree, every
// kept cluster passes the size rule, and a second run gives the same result.
TEST(Segmenter, OutputIsConsistentAndDeterministic) {
  auto setup = sim::MakeSimSetup("loop943", 1, 1.0);
  ASSERT_TRUE(setup.has_value());
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  ASSERT_TRUE(source.Next(&ls, 0.5));
  const SegmentationConfig config;
  Segmenter segmenter(config);
  SegmentationResult a, b;
  segmenter.Segment(ls.scan, &a);
  segmenter.Segment(ls.scan, &b);
  EXPECT_EQ(a.labels, b.labels);
  ASSERT_EQ(a.points.size(), b.points.size());
  ASSERT_EQ(a.ring_begin.size(), 17u);
  std::map<int32_t, std::pair<int, uint32_t>> clusters;  // label → (points, ring mask)
  int64_t outliers = 0;
  for (int32_t label : a.labels) outliers += label == kLabelOutlier;
  EXPECT_EQ(outliers, a.outlier_points);
  for (size_t r = 0; r < 16; ++r) {
    for (size_t i = a.ring_begin[r]; i < a.ring_begin[r + 1]; ++i) {
      const SegmentedPoint& p = a.points[i];
      EXPECT_EQ(p.ring, r);
      if (i > a.ring_begin[r]) {
        EXPECT_LT(a.points[i - 1].column, p.column);
      }
      EXPECT_EQ(a.labels[p.source_index], p.label);
      EXPECT_TRUE(p.label == kLabelGround || p.label >= 1);
      EXPECT_EQ(p.xyz_m, ls.scan.points[p.source_index].xyz_m);
      if (p.label >= 1) {
        ++clusters[p.label].first;
        clusters[p.label].second |= 1u << p.ring;
      }
    }
  }
  EXPECT_EQ(static_cast<int64_t>(clusters.size()), a.clusters);
  for (const auto& [label, info] : clusters) {
    const bool big = info.first >= config.min_cluster_points;
    const bool tall = std::popcount(info.second) >= config.min_cluster_rings &&
                      info.first >= config.min_spanning_cluster_points;
    EXPECT_TRUE(big || tall) << "cluster " << label;
  }
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

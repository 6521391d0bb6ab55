// LOAM features (paper §4) on simulated sweeps, checked statistically against the true classes.
#include "swlio/estimator/frontend/feature_extractor.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cstdio>
#include <set>
#include <string>

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"

namespace swlio::estimator {
namespace {

using sim::SurfaceClass;

constexpr size_t kClasses = 11;
using ClassCounts = std::array<double, kClasses>;

ClassCounts Histogram(const std::vector<FeaturePoint>& points, const sim::LabelledScan& ls) {
  ClassCounts h{};
  for (const auto& p : points) h[static_cast<size_t>(ls.cls[p.source_index])] += 1.0;
  return h;
}

double Share(const ClassCounts& h, std::initializer_list<SurfaceClass> classes) {
  double total = 0.0, in = 0.0;
  for (double v : h) total += v;
  for (SurfaceClass c : classes) in += h[static_cast<size_t>(c)];
  return total > 0.0 ? in / total : 0.0;
}

// Thin structures whose outlines are edges in a ring: poles, gantry members, insulator stacks,
// busbars, fence posts, trunks.
const std::initializer_list<SurfaceClass> kThin = {SurfaceClass::kPole, SurfaceClass::kGantry,
                                                   SurfaceClass::kInsulator, SurfaceClass::kBusbar,
                                                   SurfaceClass::kTree};
const std::initializer_list<SurfaceClass> kFlat = {SurfaceClass::kGround, SurfaceClass::kWall,
                                                   SurfaceClass::kFence, SurfaceClass::kTransformer,
                                                   SurfaceClass::kTrench};

// Deviation from straightness of the true hit points of ring neighbours i−W..i+W of segmented
// point i: the largest distance from their principal line, metres. Noise-free geometry: a
// window on a plane is straight (to a few mm), a window across a corner, a pole or a depth
// step is not.
double TrueBend(const SegmentationResult& seg, const sim::LabelledScan& ls, size_t i, size_t w) {
  const SegmentedPoint& p = seg.points[i];
  const size_t begin = seg.ring_begin[p.ring];
  const size_t end = seg.ring_begin[p.ring + 1u];
  const size_t lo = i >= begin + w ? i - w : begin;
  const size_t hi = std::min(end, i + w + 1);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t j = lo; j < hi; ++j) mean += ls.p_world[seg.points[j].source_index];
  mean /= static_cast<double>(hi - lo);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t j = lo; j < hi; ++j) {
    const Eigen::Vector3d d = ls.p_world[seg.points[j].source_index] - mean;
    cov += d * d.transpose();
  }
  const Eigen::Vector3d axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(2);
  double worst = 0.0;
  for (size_t j = lo; j < hi; ++j) {
    const Eigen::Vector3d d = ls.p_world[seg.points[j].source_index] - mean;
    worst = std::max(worst, (d - d.dot(axis) * axis).norm());
  }
  return worst;
}

/// Fraction of `points` whose true ring window bends by more than `bend_m`.
double BentShare(const std::vector<FeaturePoint>& points,
                 const SegmentationResult& seg,
                 const sim::LabelledScan& ls,
                 const std::vector<int64_t>& seg_index,
                 double bend_m) {
  if (points.empty()) return 0.0;
  double bent = 0.0;
  for (const auto& p : points) {
    const auto i = static_cast<size_t>(seg_index[p.source_index]);
    bent += TrueBend(seg, ls, i, 5) > bend_m ? 1.0 : 0.0;
  }
  return bent / static_cast<double>(points.size());
}

struct Case {
  std::string scenario;
  uint64_t seed;
  double t_min_s;
};

class FeatureTest : public ::testing::TestWithParam<Case> {};

TEST_P(FeatureTest, EdgesOnThinStructuresPlanesOnSurfaces) {
  const Case& c = GetParam();
  auto setup = sim::MakeSimSetup(c.scenario, c.seed, c.t_min_s + 0.5);
  ASSERT_TRUE(setup.has_value());
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  ASSERT_TRUE(source.Next(&ls, c.t_min_s));
  Segmenter segmenter(SegmentationConfig{});
  SegmentationResult seg;
  segmenter.Segment(ls.scan, &seg);
  const FeatureConfig config;
  FeatureExtractor extractor(config);
  FeatureSet f;
  extractor.Extract(seg, &f);

  // Per-sector budgets and set inclusions.
  const size_t sectors = 16 * static_cast<size_t>(config.sectors_per_ring);
  EXPECT_LE(f.edges_sharp.size(), sectors * static_cast<size_t>(config.max_sharp_edges_per_sector));
  EXPECT_LE(f.edges.size(), sectors * static_cast<size_t>(config.max_edges_per_sector));
  EXPECT_LE(f.planes_flat.size(), sectors * static_cast<size_t>(config.max_flat_planes_per_sector));
  std::set<uint32_t> edge_ids, plane_ids;
  for (const auto& p : f.edges) edge_ids.insert(p.source_index);
  for (const auto& p : f.planes) plane_ids.insert(p.source_index);
  for (const auto& p : f.edges_sharp) EXPECT_TRUE(edge_ids.count(p.source_index));
  for (const auto& p : f.planes_flat) EXPECT_TRUE(plane_ids.count(p.source_index));
  for (const auto& p : f.edges) {
    EXPECT_FALSE(plane_ids.count(p.source_index));
    EXPECT_NE(seg.labels[p.source_index], kLabelGround);
    EXPECT_GT(p.curvature, config.edge_threshold_m2);
  }
  // Every reliable ground point feeds the planar set: most ground points are there.
  size_t ground_in_planes = 0;
  for (uint32_t id : plane_ids) ground_in_planes += seg.labels[id] == kLabelGround;
  EXPECT_GE(static_cast<double>(ground_in_planes), 0.9 * static_cast<double>(seg.ground_points));

  // Statistics against the truth: edges lie where the true geometry bends (corners, poles,
  // gantry members, depth steps), planes where it does not, and on surface classes.
  std::vector<int64_t> seg_index(ls.scan.points.size(), -1);
  std::vector<FeaturePoint> all;
  for (size_t i = 0; i < seg.points.size(); ++i) {
    seg_index[seg.points[i].source_index] = static_cast<int64_t>(i);
    all.push_back({seg.points[i].xyz_m, 0, 0.0f, seg.points[i].source_index, seg.points[i].ring});
  }
  constexpr double kBendM = 0.05;
  const double bent_all = BentShare(all, seg, ls, seg_index, kBendM);
  const double bent_edges = BentShare(f.edges, seg, ls, seg_index, kBendM);
  const double bent_sharp = BentShare(f.edges_sharp, seg, ls, seg_index, kBendM);
  const double bent_planes = BentShare(f.planes, seg, ls, seg_index, kBendM);
  const double bent_flat = BentShare(f.planes_flat, seg, ls, seg_index, kBendM);
  const ClassCounts planes = Histogram(f.planes, ls);
  const ClassCounts flat = Histogram(f.planes_flat, ls);
  const ClassCounts edges = Histogram(f.edges, ls);
  std::printf(
      "%s/%llu: bent share: cloud %.3f edges %.3f sharp %.3f planes %.3f flat %.3f | "
      "edges %zu (thin %.2f, ground %.3f) sharp %zu planes %zu (surfaces %.3f) flat %zu "
      "(surfaces %.3f) occluded %lld parallel %lld\n",
      c.scenario.c_str(), static_cast<unsigned long long>(c.seed), bent_all, bent_edges, bent_sharp,
      bent_planes, bent_flat, f.edges.size(), Share(edges, kThin),
      Share(edges, {SurfaceClass::kGround}), f.edges_sharp.size(), f.planes.size(),
      Share(planes, kFlat), f.planes_flat.size(), Share(flat, kFlat),
      static_cast<long long>(f.occluded), static_cast<long long>(f.parallel));
  EXPECT_GT(f.edges.size(), 30u);
  EXPECT_GT(f.planes.size(), 5000u);
  EXPECT_LT(Share(edges, {SurfaceClass::kGround}), 0.05);
  EXPECT_GT(bent_edges, 0.6);
  EXPECT_GT(bent_sharp, 0.7);
  EXPECT_GT(bent_edges, 4.0 * bent_all);
  EXPECT_LT(bent_flat, 0.08);
  EXPECT_LT(bent_planes, 0.5 * bent_all);
  EXPECT_GT(Share(planes, kFlat), 0.9);
  EXPECT_GT(Share(flat, kFlat), 0.8);
  EXPECT_GT(f.occluded, 0);
}

INSTANTIATE_TEST_SUITE_P(Scenarios,
                         FeatureTest,
                         ::testing::Values(Case{"short", 1, 0.5},
                                           Case{"loop943", 2, 0.5},
                                           Case{"aggressive", 3, 1.0},
                                           Case{"short", 2, 6.0}),
                         [](const auto& info) {
                           return info.param.scenario + "_seed" + std::to_string(info.param.seed) +
                                  "_t" + std::to_string(static_cast<int>(info.param.t_min_s));
                         });

}  // namespace
}  // namespace swlio::estimator

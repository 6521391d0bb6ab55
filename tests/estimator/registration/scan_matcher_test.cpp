#include "swlio/estimator/registration/scan_matcher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Points on a box-shaped yard: ground z = 0, walls x = ±10, y = ±8, plus four vertical poles.
struct Scene {
  std::vector<Eigen::Vector3d> planes;
  std::vector<Eigen::Vector3d> edges;
};

Scene MakeScene(double step, std::mt19937* rng, double noise, bool ground_only = false) {
  std::normal_distribution<double> n(0.0, noise);
  Scene s;
  for (double a = -9.5; a <= 9.5; a += step) {
    for (double b = -7.5; b <= 7.5; b += step) s.planes.emplace_back(a, b, n(*rng));
  }
  if (ground_only) return s;
  for (double a = -7.5; a <= 7.5; a += step) {
    for (double z = 0.2; z <= 3.0; z += step) {
      s.planes.emplace_back(-10.0 + n(*rng), a, z);
      s.planes.emplace_back(10.0 + n(*rng), a, z);
    }
  }
  for (double a = -9.5; a <= 9.5; a += step) {
    for (double z = 0.2; z <= 3.0; z += step) s.planes.emplace_back(a, 8.0 + n(*rng), z);
  }
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(3, 2), Eigen::Vector2d(-4, 5),
                                   Eigen::Vector2d(6, -5), Eigen::Vector2d(-2, -3)}) {
    for (double z = 0.1; z <= 4.0; z += step) {
      s.edges.emplace_back(c.x() + n(*rng), c.y() + n(*rng), z);
    }
  }
  return s;
}

std::vector<Eigen::Vector3d> ToLidar(const std::vector<Eigen::Vector3d>& world,
                                     const Eigen::Isometry3d& T_world_lidar) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : world) out.push_back(T_world_lidar.inverse() * p);
  return out;
}

Eigen::Isometry3d Pose(double x, double y, double z, double roll, double pitch, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::QuatFromRpy(roll, pitch, yaw).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

TEST(ScanMatcher, RecoversThePoseFromAPerturbedGuess) {
  std::mt19937 rng(3);
  const Scene map_scene = MakeScene(0.15, &rng, 0.005);
  VoxelMap planes, edges;
  planes.Insert(map_scene.planes);
  edges.Insert(map_scene.edges);
  const Eigen::Isometry3d truth = Pose(1.0, -0.5, 0.7, 1 * kDeg, -2 * kDeg, 30 * kDeg);
  const Scene scan = MakeScene(0.4, &rng, 0.01);
  const Eigen::Isometry3d guess = truth * Pose(0.25, -0.2, 0.1, 2 * kDeg, -1 * kDeg, 4 * kDeg);
  const MatchResult r = ScanMatcher().Match(ToLidar(scan.planes, truth), ToLidar(scan.edges, truth),
                                            planes, edges, guess);
  EXPECT_TRUE(r.converged);
  const Eigen::Isometry3d err = truth.inverse() * r.T_world_lidar;
  EXPECT_LT(err.translation().norm(), 0.01);
  EXPECT_LT(lie::Log(err.linear()).norm(), 0.1 * kDeg);
  EXPECT_GT(r.plane_inliers, scan.planes.size() * 9 / 10);
  EXPECT_GT(r.edge_inliers, scan.edges.size() / 2);
  EXPECT_GT(r.hessian_eigenvalues(0), 10.0) << "every direction is constrained";
}

TEST(ScanMatcher, GroundOnlyIsDegenerateInThreeDirections) {
  std::mt19937 rng(4);
  const Scene map_scene = MakeScene(0.15, &rng, 0.005, true);
  VoxelMap planes, edges;
  planes.Insert(map_scene.planes);
  const Eigen::Isometry3d truth = Pose(0.5, 0.5, 0.8, 0, 0, 10 * kDeg);
  const Scene scan = MakeScene(0.4, &rng, 0.01, true);
  const MatchResult r = ScanMatcher().Match(ToLidar(scan.planes, truth), {}, planes, edges,
                                            truth * Pose(0, 0, 0.05, 1 * kDeg, 0, 0));
  // x, y and yaw are unobservable from a flat ground: three eigenvalues near zero (only the
  // noise-tilted local normals constrain them), three large (z, roll, pitch).
  EXPECT_LT(r.hessian_eigenvalues(2), 0.003 * r.hessian_eigenvalues(5));
  EXPECT_GT(r.hessian_eigenvalues(3), 0.01 * r.hessian_eigenvalues(5));
  EXPECT_GT(r.hessian_eigenvalues(3), 10.0 * r.hessian_eigenvalues(2));
  const Eigen::Isometry3d err = truth.inverse() * r.T_world_lidar;
  EXPECT_NEAR(err.translation().z(), 0.0, 0.01);  // the observable part is still recovered
}

// A 0.3 m wall inside the yard, mapped so far from the west: the map holds its west face
// (x = 2). The sweep, from the east, sees its east face (x = 2.3), which the map does not have
// yet. Paired with the west face, 0.3 m away, those points would pull the pose west.
TEST(ScanMatcher, ANewFaceOfAThinWallIsNotPairedWithTheFaceSeenBefore) {
  std::mt19937 rng(5);
  Scene map_scene = MakeScene(0.15, &rng, 0.005);
  Scene scan = MakeScene(0.4, &rng, 0.005);
  for (double y = -3.0; y <= 3.0; y += 0.15) {
    for (double z = 0.2; z <= 3.0; z += 0.15) map_scene.planes.emplace_back(2.0, y, z);
  }
  const size_t yard_points = scan.planes.size();
  for (double y = -3.0; y <= 3.0; y += 0.2) {
    for (double z = 0.6; z <= 3.0; z += 0.2) scan.planes.emplace_back(2.3, y, z);
  }
  VoxelMap planes, edges;
  planes.Insert(map_scene.planes);
  edges.Insert(map_scene.edges);
  const Eigen::Isometry3d truth = Pose(5.0, 1.0, 0.7, 0, 0, 20 * kDeg);  // east of the wall
  const auto planes_lidar = ToLidar(scan.planes, truth);
  const auto edges_lidar = ToLidar(scan.edges, truth);

  const auto pairs_at_truth = [&](const ScanMatcher& matcher) {
    std::vector<PlaneCorrespondence> paired;
    std::vector<LineCorrespondence> lines;
    matcher.Associate(planes_lidar, edges_lidar, planes, edges, truth, &paired, &lines);
    return paired;
  };
  const auto far_face = [&](const std::vector<PlaneCorrespondence>& paired) {
    return std::count_if(paired.begin(), paired.end(),
                         [&](const PlaneCorrespondence& c) { return c.index >= yard_points; });
  };
  const auto far_points = static_cast<std::ptrdiff_t>(scan.planes.size() - yard_points);
  const std::vector<PlaneCorrespondence> paired = pairs_at_truth(ScanMatcher());
  EXPECT_LE(far_face(paired), far_points / 20);
  EXPECT_GT(paired.size(), yard_points * 9 / 10);
  EXPECT_GE(far_face(pairs_at_truth(ScanMatcher({.refined_max_residual_m = 1.0}))),
            far_points * 3 / 4);

  // From a guess 0.25 m off, the first association (wide gate) still finds the yard.
  const Eigen::Isometry3d guess = truth * Pose(0.2, -0.15, 0.0, 0, 0, 2 * kDeg);
  const MatchResult r = ScanMatcher().Match(planes_lidar, edges_lidar, planes, edges, guess);
  EXPECT_LT((truth.inverse() * r.T_world_lidar).translation().norm(), 0.005);

  // With the wide gate throughout, the far face pulls the pose west.
  const MatchResult wide = ScanMatcher({.refined_max_residual_m = 1.0})
                               .Match(planes_lidar, edges_lidar, planes, edges, guess);
  EXPECT_GT((truth.inverse() * wide.T_world_lidar).translation().norm(), 0.01);
}

// Edge features on a flat face (the smoothness of a few points over its threshold by noise, or
// cut short by a silhouette) scatter over it in the map; five neighbours of such a scatter are
// no line, though they can happen to lie longer than wide. A corner's points lie along it.
TEST(ScanMatcher, EdgePointsScatteredOverAFaceMakeNoLine) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> across(-0.35, 0.35), up(0.0, 4.0), inside(0.5, 3.5);
  std::normal_distribution<double> noise(0.0, 0.015);
  std::vector<Eigen::Vector3d> map_edges, corner_queries, face_queries;
  for (double z = 0.1; z <= 4.0; z += 0.12) map_edges.emplace_back(noise(rng), noise(rng), z);
  for (int i = 0; i < 150; ++i) map_edges.emplace_back(across(rng), 5.0 + noise(rng), up(rng));
  for (int i = 0; i < 40; ++i) corner_queries.emplace_back(0.0, 0.0, inside(rng));
  for (int i = 0; i < 200; ++i) face_queries.emplace_back(across(rng), 5.0, inside(rng));
  VoxelMap planes, edges;
  edges.Insert(map_edges);
  const auto lines_found = [&](const ScanMatcher& matcher,
                               const std::vector<Eigen::Vector3d>& queries) {
    std::vector<PlaneCorrespondence> paired;
    std::vector<LineCorrespondence> lines;
    matcher.Associate({}, queries, planes, edges, Eigen::Isometry3d::Identity(), &paired, &lines);
    return static_cast<double>(lines.size()) / static_cast<double>(queries.size());
  };
  EXPECT_GE(lines_found(ScanMatcher(), corner_queries), 0.95);
  EXPECT_LE(lines_found(ScanMatcher(), face_queries), 0.3);
  // LOAM's λ1 ≥ 3·λ2 takes a good part of the scatter for lines.
  EXPECT_GE(lines_found(ScanMatcher({.line_min_ratio = 3.0}), face_queries), 0.4);
}

TEST(ScanMatcher, TooFewCorrespondencesDoNotConverge) {
  VoxelMap planes, edges;
  const MatchResult r = ScanMatcher().Match({Eigen::Vector3d(1, 2, 3)}, {}, planes, edges,
                                            Eigen::Isometry3d::Identity());
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.plane_inliers, 0u);
  EXPECT_TRUE(r.T_world_lidar.isApprox(Eigen::Isometry3d::Identity()));
}

}  // namespace
}  // namespace swlio::estimator

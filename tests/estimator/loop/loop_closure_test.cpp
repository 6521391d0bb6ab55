// Loop closure (issue 8) on a synthetic scene: ground and boxes sampled as points, keyframe
// clouds cut from it around the true pose, odometry poses that drift. Checks that the drifted
// loop is found and corrected, that each accepted loop edge agrees with the truth, and that
// the verifier refuses a wrong place and a corridor.
#include "swlio/estimator/loop/loop_closure.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "box_yard.h"
#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Points = std::vector<Vec3>;
using test::BoxYard;
using test::Corridor;
using test::Cut;
using test::kImuLidar;
using test::Pose;
using test::RectangleDrive;
using test::Scene;

TEST(LoopClosure, ClosesADriftedLoopOntoTheTruth) {
  const Scene scene = BoxYard(7);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(12.0);
  LoopClosure closure{LoopClosureConfig{}};
  // Odometry: each 0.5 m step turns 0.25 mrad too far (3.7° over the drive), is 0.4 % too
  // long and climbs 1 mm.
  const Eigen::Isometry3d drift = Pose({0.002, 0.0, 0.001}, 2.5e-4);
  Eigen::Isometry3d odom = truth[0];
  size_t optimized = 0;
  for (size_t k = 0; k < truth.size(); ++k) {
    if (k > 0) odom = odom * truth[k - 1].inverse() * truth[k] * drift;
    // The sensor sees the scene from the true pose; the odometry believes `odom`.
    KeyframeCloud kf = Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]);
    kf.T_world_imu = odom;
    optimized += closure.AddKeyframe(kf).optimized ? 1 : 0;
  }
  const double odom_error_m = (odom.translation() - truth.back().translation()).norm();
  const Eigen::Isometry3d corrected = closure.T_map_odom() * odom;
  const double error_m = (corrected.translation() - truth.back().translation()).norm();
  const LoopClosureStats& st = closure.stats();
  std::printf(
      "[ loop ] %zu nodes, %zu attempts, %zu accepted, %zu rejected; end error %.3f m "
      "odometry, %.3f m corrected\n",
      st.nodes, st.attempts, st.accepted, st.rejected, odom_error_m, error_m);
  EXPECT_GT(odom_error_m, 1.0);
  ASSERT_GE(st.accepted, 1u);
  EXPECT_EQ(optimized, st.accepted);
  EXPECT_LT(error_m, 0.1);
  // Every accepted loop edge is the true relative pose of its two nodes.
  for (const LoopAttempt& a : closure.attempts()) {
    std::printf(
        "[ loop ] %zu -> %zu (%.2f m apart): %s, fitness %.2f, λmin %.0f, correction "
        "%.2f m %.3f rad\n",
        a.candidate, a.node, a.distance_m, ToString(a.check.verdict), a.check.fitness,
        a.check.min_eigenvalue, a.check.correction_m, a.check.correction_rad);
    if (a.check.verdict != LoopVerdict::kAccepted) continue;
    const auto true_pose = [&](size_t node) {
      return truth[static_cast<size_t>(closure.node(node).t_ns / 500'000'000)];
    };
    const Eigen::Isometry3d want = true_pose(a.candidate).inverse() * true_pose(a.node);
    const Eigen::Isometry3d got = a.check.T_candidate_lidar * kImuLidar.inverse();
    const Eigen::Isometry3d e = want.inverse() * got;
    EXPECT_LT(e.translation().norm(), 0.05) << "loop " << a.candidate << " -> " << a.node;
    EXPECT_LT(Eigen::AngleAxisd(e.rotation()).angle(), 0.005);
  }
  // The optimized trajectory: every node within 0.25 m of the truth (odometry: up to ~1 m at
  // the end). What is left is mostly the odometry's 0.4 % scale error, which the loop cannot
  // see along the far sides (0.16 m over 40 m).
  double worst_m = 0.0;
  for (size_t i = 0; i < closure.nodes(); ++i) {
    const size_t k = static_cast<size_t>(closure.node(i).t_ns / 500'000'000);
    worst_m =
        std::max(worst_m, (closure.T_map_imu(i).translation() - truth[k].translation()).norm());
    const Eigen::Isometry3d again =
        closure.CorrectedPose(closure.node(i).t_ns, closure.node(i).T_world_imu);
    EXPECT_TRUE(again.isApprox(closure.T_map_imu(i), 1e-9));
  }
  std::printf("[ loop ] worst node error after optimization %.3f m\n", worst_m);
  EXPECT_LT(worst_m, 0.25);
}

TEST(LoopClosure, NoLoopBeforeTheRobotComesBack) {
  const Scene scene = BoxYard(7);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  LoopClosure closure{LoopClosureConfig{}};
  // Only the first three sides: no place is seen twice (30 s apart) within 10 m.
  for (size_t k = 0; k < 170; ++k) {
    KeyframeCloud kf = Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]);
    kf.T_world_imu = truth[k];
    closure.AddKeyframe(kf);
  }
  EXPECT_GT(closure.nodes(), 80u);
  EXPECT_EQ(closure.stats().accepted, 0u);
  EXPECT_TRUE(closure.T_map_odom().isApprox(Eigen::Isometry3d::Identity(), 1e-9));
}

LoopSubmap SubmapAround(const Scene& s, const Eigen::Isometry3d& T_world_imu) {
  LoopClosureConfig config;
  LoopSubmap submap(config.submap);
  const KeyframeCloud kf = Cut(s, 0, T_world_imu);
  const auto in_imu = [&](const Points& pts) {
    Points out;
    for (const Vec3& p : pts) out.push_back(kImuLidar * p);
    return out;
  };
  submap.planes.Insert(in_imu(kf.planes_lidar));
  submap.edges.Insert(in_imu(kf.edges_lidar));
  return submap;
}

TEST(LoopVerifier, AcceptsTheSamePlaceFromADriftedGuess) {
  const Scene scene = BoxYard(7);
  const Eigen::Isometry3d here = Pose({20.0, 0.0, 0.5}, 0.0);
  const LoopSubmap submap = SubmapAround(scene, here);
  const Eigen::Isometry3d seen_from = Pose({21.0, 0.5, 0.5}, 0.05);
  const KeyframeCloud kf = Cut(scene, 0, seen_from);
  const Eigen::Isometry3d truth = here.inverse() * seen_from * kImuLidar;
  const Eigen::Isometry3d guess = truth * Pose({0.8, -0.6, 0.1}, -0.04);
  const LoopCheck c =
      VerifyLoop(LoopClosureConfig{}, kf.planes_lidar, kf.edges_lidar, submap, guess);
  std::printf(
      "[ verify ] same place: %s, fitness %.2f, %zu inliers, λmin %.1f, correction %.2f m\n",
      ToString(c.verdict), c.fitness, c.inliers, c.min_eigenvalue, c.correction_m);
  EXPECT_EQ(c.verdict, LoopVerdict::kAccepted);
  EXPECT_LT((truth.inverse() * c.T_candidate_lidar).translation().norm(), 0.02);
}

TEST(LoopVerifier, RefusesAnotherPlace) {
  const Scene scene = BoxYard(7);
  const LoopSubmap submap = SubmapAround(scene, Pose({20.0, 0.0, 0.5}, 0.0));
  // The cloud is from the far side of the yard, but the guess says "here".
  const KeyframeCloud kf = Cut(scene, 0, Pose({20.0, 25.0, 0.5}, 0.0));
  const LoopCheck c =
      VerifyLoop(LoopClosureConfig{}, kf.planes_lidar, kf.edges_lidar, submap, kImuLidar);
  std::printf("[ verify ] other place: %s, fitness %.2f, %zu inliers\n", ToString(c.verdict),
              c.fitness, c.inliers);
  EXPECT_NE(c.verdict, LoopVerdict::kAccepted);
}

TEST(LoopVerifier, RefusesACorridorThatDoesNotFixThePositionAlongIt) {
  const Scene scene = Corridor();
  const LoopSubmap submap = SubmapAround(scene, Pose({0.0, 0.0, 0.5}, 0.0));
  const KeyframeCloud kf = Cut(scene, 0, Pose({1.0, 0.0, 0.5}, 0.0));
  const LoopCheck c =
      VerifyLoop(LoopClosureConfig{}, kf.planes_lidar, kf.edges_lidar, submap, kImuLidar);
  std::printf("[ verify ] corridor: %s, fitness %.2f, λmin %.2f\n", ToString(c.verdict), c.fitness,
              c.min_eigenvalue);
  EXPECT_EQ(c.verdict, LoopVerdict::kDegenerate);
}

TEST(LoopClosureConfig, DefaultsAreValidAndErrorsNamed) {
  EXPECT_TRUE(LoopClosureConfig{}.Validate().empty());
  LoopClosureConfig c;
  c.search_radius_m = 0.0;
  c.min_fitness = 1.5;
  c.coarse.max_iterations = 0;
  const ConfigIssues issues = c.Validate();
  ASSERT_EQ(issues.size(), 3u);
  EXPECT_EQ(issues[0].key, "search_radius_m");
  EXPECT_EQ(issues[1].key, "coarse.max_iterations");
  EXPECT_EQ(issues[2].key, "min_fitness");
}

}  // namespace
}  // namespace swlio::estimator

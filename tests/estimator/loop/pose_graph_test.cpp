// Pose graph (issue 8): the relative-pose factor's residual and analytic Jacobians, and a
// drifted loop pulled back onto the truth by one loop edge.
#include "swlio/estimator/loop/pose_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "jacobian_check.h"
#include "swlio/core/lie.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/loop/relative_pose_factor.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Block = std::vector<double>;

Eigen::Isometry3d Pose(const Vec3& p, const Vec3& rotation_vector) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::Exp(rotation_vector);
  T.translation() = p;
  return T;
}

Block ToBlock(const Eigen::Isometry3d& T) {
  Block x(kPoseSize);
  PoseToParameters(T, x.data());
  return x;
}

TEST(RelativePoseFactor, ZeroAtTheMeasurementAndJacobiansMatch) {
  const Eigen::Isometry3d T_i = Pose({3.0, -1.0, 0.4}, {0.1, -0.2, 1.3});
  const Eigen::Isometry3d T_j = Pose({5.5, 2.0, 0.1}, {-0.3, 0.2, 2.1});
  Mat6 S = DiagonalSqrtInformation(0.05, 0.01);
  S(0, 4) = 3.0;  // a full square root, not only a diagonal
  const auto exact = RelativePoseFactor::Create(T_i.inverse() * T_j, S);
  ASSERT_NE(exact, nullptr);
  std::vector<Block> x = {ToBlock(T_i), ToBlock(T_j)};
  EXPECT_LT(test::EvaluateResidual(*exact, x).norm(), 1e-9);

  // Away from the measurement (rotation error ~0.3 rad), where J_r⁻¹ matters.
  const Eigen::Isometry3d measured = T_i.inverse() * T_j * Pose({0.2, -0.1, 0.3}, {0.2, 0.1, -0.2});
  const auto f = RelativePoseFactor::Create(measured, S);
  ASSERT_NE(f, nullptr);
  const PoseManifold pose;
  const test::JacobianErrors e = test::CheckJacobians(*f, x, {&pose, &pose});
  for (size_t k = 0; k < e.ambient.size(); ++k)
    std::printf("[ jacobian ] RelativePoseFactor block %zu: ambient %.2e, tangent %.2e\n", k,
                e.ambient[k], e.tangent[k]);
  EXPECT_LT(e.Worst(), 1e-7);

  Mat6 bad = S;
  bad(2, 2) = std::nan("");
  EXPECT_EQ(RelativePoseFactor::Create(measured, bad), nullptr);
}

// A 20 × 10 m rectangle driven in 1 m steps, back to the start.
std::vector<Eigen::Isometry3d> Rectangle() {
  std::vector<Eigen::Isometry3d> truth;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int side = 0; side < 4; ++side) {
    const int steps = side % 2 == 0 ? 20 : 10;
    for (int s = 0; s < steps; ++s) {
      truth.push_back(T);
      T = T * Pose({1.0, 0.0, 0.0}, {0.0, 0.0, s == steps - 1 ? std::numbers::pi / 2 : 0.0});
    }
  }
  truth.push_back(T);
  return truth;
}

/// Nodes at the odometry's poses (each step turning `yaw_drift_rad` too far) and odometry
/// edges between them.
void AddDriftedChain(const std::vector<Eigen::Isometry3d>& truth,
                     double yaw_drift_rad,
                     PoseGraph* graph) {
  Eigen::Isometry3d odom = truth[0];
  graph->AddNode(odom);
  const Eigen::Isometry3d drift = Pose({0.0, 0.0, 0.0}, {0.0, 0.0, yaw_drift_rad});
  for (size_t k = 1; k < truth.size(); ++k) {
    const Eigen::Isometry3d step = truth[k - 1].inverse() * truth[k] * drift;
    odom = odom * step;
    graph->AddNode(odom);
    ASSERT_TRUE(graph->AddOdometryEdge(k - 1, k, step, DiagonalSqrtInformation(0.02, 0.002)));
  }
}

double WorstError(const PoseGraph& graph, const std::vector<Eigen::Isometry3d>& truth) {
  double worst_m = 0.0;
  for (size_t k = 0; k < truth.size(); ++k)
    worst_m = std::max(worst_m, (graph.pose(k).translation() - truth[k].translation()).norm());
  return worst_m;
}

// The odometry turns 3 mrad too far each step (10° and 2 m of end error after 60 steps): one
// loop edge (the truth between the last node and the first) brings the loop back to within
// a tenth of that.
TEST(PoseGraph, OneLoopEdgeRemovesTheDriftOfALoop) {
  const std::vector<Eigen::Isometry3d> truth = Rectangle();
  PoseGraph graph;
  AddDriftedChain(truth, 3e-3, &graph);
  const size_t last = truth.size() - 1;
  const double drift_m = WorstError(graph, truth);
  EXPECT_GT(drift_m, 1.5);
  EXPECT_FALSE(graph.AddLoopEdge(0, last + 1, Eigen::Isometry3d::Identity(), Mat6::Identity()));
  EXPECT_FALSE(graph.AddLoopEdge(3, 3, Eigen::Isometry3d::Identity(), Mat6::Identity()));
  ASSERT_TRUE(graph.AddLoopEdge(0, last, truth[0].inverse() * truth[last],
                                DiagonalSqrtInformation(0.05, 0.005)));
  const PoseGraphSummary summary = graph.Optimize();
  ASSERT_TRUE(summary.solved);
  EXPECT_LT(summary.final_cost, 0.1 * summary.initial_cost);
  const double worst_m = WorstError(graph, truth);
  std::printf("[ graph ] worst error %.3f m, after the loop edge %.3f m\n", drift_m, worst_m);
  EXPECT_LT(worst_m, 0.1 * drift_m);
  EXPECT_EQ(graph.loop_edges(), 1u);
  EXPECT_TRUE(graph.pose(0).isApprox(truth[0]));  // the gauge stays
}

// A loop edge that passed verification but is wrong (it says node 45 lies 1 m from node 5;
// they are 10 m apart) cannot be satisfied together with the odometry and the right loop: the
// consistency check switches it off, and the result is the right loop's.
TEST(PoseGraph, TheConsistencyCheckSwitchesOffAWrongLoop) {
  const std::vector<Eigen::Isometry3d> truth = Rectangle();
  const size_t last = truth.size() - 1;
  const Mat6 S_loop = DiagonalSqrtInformation(0.05, 0.005);
  PoseGraph graph(0.0, 22.5);
  AddDriftedChain(truth, 1e-3, &graph);
  ASSERT_TRUE(graph.AddLoopEdge(5, 45, Pose({1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}), S_loop));
  ASSERT_TRUE(graph.AddLoopEdge(0, last, truth[0].inverse() * truth[last], S_loop));
  const PoseGraphSummary summary = graph.Optimize();
  ASSERT_TRUE(summary.solved);
  std::printf("[ graph ] loops switched off %zu; χ² of the right loop %.2f; worst error %.3f m\n",
              summary.loops_switched_off, graph.LoopChi2(1), WorstError(graph, truth));
  EXPECT_EQ(summary.loops_switched_off, 1u);
  EXPECT_FALSE(graph.LoopActive(0));
  EXPECT_TRUE(graph.LoopActive(1));
  EXPECT_LT(graph.LoopChi2(1), 22.5);
  EXPECT_LT(WorstError(graph, truth), 0.1);
  // Without the check the wrong loop bends the whole graph.
  PoseGraph unchecked;
  AddDriftedChain(truth, 1e-3, &unchecked);
  unchecked.AddLoopEdge(5, 45, Pose({1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}), S_loop);
  unchecked.AddLoopEdge(0, last, truth[0].inverse() * truth[last], S_loop);
  unchecked.Optimize();
  EXPECT_GT(WorstError(unchecked, truth), 1.0);
}

}  // namespace
}  // namespace swlio::estimator

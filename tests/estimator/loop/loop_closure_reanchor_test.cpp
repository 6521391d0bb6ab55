// An operator's pose hint while mapping re-anchors the map frame (LoopClosure::Reanchor, issue
// 34): every node, the correction and later nodes move by the same rigid transform, so the map
// keeps its shape; with GNSS the map frame belongs to ENU and the hint is refused.
#include <gtest/gtest.h>

#include <vector>

#include "box_yard.h"
#include "swlio/estimator/loop/loop_closure.h"

namespace swlio::estimator {
namespace {

std::vector<KeyframeCloud> Keyframes(size_t n) {
  const test::Scene scene = test::BoxYard(7);
  const std::vector<Eigen::Isometry3d> truth = test::RectangleDrive(0.0);
  std::vector<KeyframeCloud> out;
  for (size_t k = 0; k < n; ++k) {
    out.push_back(test::Cut(scene, static_cast<int64_t>(k) * 500'000'000, truth[k]));
    out.back().T_world_imu = truth[k];
  }
  return out;
}

TEST(LoopClosureReanchor, MovesEveryNodeAndWhatFollowsByTheSameTransform) {
  const std::vector<KeyframeCloud> kf = Keyframes(40);
  LoopClosure moved(LoopClosureConfig{}), kept(LoopClosureConfig{});
  for (size_t k = 0; k < 20; ++k) moved.AddKeyframe(kf[k]), kept.AddKeyframe(kf[k]);
  const Eigen::Isometry3d A = test::Pose({35.0, -12.0, 0.0}, 1.3);
  ASSERT_TRUE(moved.Reanchor(A));
  for (size_t k = 20; k < 40; ++k) moved.AddKeyframe(kf[k]), kept.AddKeyframe(kf[k]);
  ASSERT_EQ(moved.nodes(), kept.nodes());
  ASSERT_GT(moved.nodes(), 10u);
  EXPECT_TRUE(moved.T_map_odom().isApprox(A * kept.T_map_odom(), 1e-9));
  const std::vector<MapNode> a = moved.MapPath(), b = kept.MapPath();
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_LT((a[i].T_map_imu.translation() - (A * b[i].T_map_imu).translation()).norm(), 1e-6)
        << "node " << i;
    EXPECT_TRUE(a[i].T_map_imu.linear().isApprox((A * b[i].T_map_imu).linear(), 1e-9));
  }
  const SavedMap saved = moved.ToSavedMap();
  ASSERT_FALSE(saved.nodes.empty());
  EXPECT_LT((saved.nodes.front().T_map_imu.translation() -
             (A * kept.ToSavedMap().nodes.front().T_map_imu).translation())
                .norm(),
            1e-6);
}

TEST(LoopClosureReanchor, RefusedWhenGnssTiesTheMapToEnu) {
  LoopClosureConfig config;
  config.gnss.enabled = true;
  LoopClosure closure(config);
  EXPECT_FALSE(closure.Reanchor(test::Pose({1.0, 0.0, 0.0}, 0.0)));
  EXPECT_TRUE(closure.T_map_odom().isApprox(Eigen::Isometry3d::Identity()));
}

}  // namespace
}  // namespace swlio::estimator

// Operator hints to the map localizer (issue 34: rviz2's /initialpose, swlioctl relocalize) on
// the synthetic yards of map_localizer_test.cpp: a hint near the truth localizes at once, even
// where every place has a look-alike (where relocalization without one never commits); a hint
// far from the truth, or off the map, is refused and changes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "box_yard.h"
#include "box_yard_map.h"
#include "swlio/estimator/map/map_localizer.h"

namespace swlio::estimator {
namespace {

using test::Pose;
using test::RectangleDrive;
using test::Scene;

const Eigen::Isometry3d kOdomFromWorld = Pose({-31.0, 12.0, 0.0}, 1.2);

KeyframeCloud KeyframeAt(const Scene& scene, const Eigen::Isometry3d& truth, int64_t t_ns) {
  KeyframeCloud kf = test::Cut(scene, t_ns, truth);
  kf.T_world_imu = kOdomFromWorld * truth;
  return kf;
}

/// A hint at the truth moved by (dx, dy) m and dyaw rad.
LocalizationHint HintNear(const Eigen::Isometry3d& truth, double dx, double dy, double dyaw) {
  LocalizationHint h;
  h.x_m = truth.translation().x() + dx;
  h.y_m = truth.translation().y() + dy;
  h.yaw_rad = std::atan2(truth.linear()(1, 0), truth.linear()(0, 0)) + dyaw;
  return h;
}

double PositionError(const MapLocalizer& l, const KeyframeCloud& kf, const Eigen::Isometry3d& T) {
  return ((l.T_map_odom() * kf.T_world_imu).translation() - T.translation()).norm();
}

TEST(MapLocalizerHint, ARoughHintLocalizesAtOnce) {
  const Scene scene = test::BoxYard(7);
  MapLocalizer localizer(test::BoxYardMap(scene, 2, 1'000'000), LocalizationConfig{});
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  const KeyframeCloud kf = KeyframeAt(scene, truth[40], 40);
  // rviz2's click: 0.8 m and 8° off, with its default σ (0.5 m, 0.26 rad).
  const HintOutcome out = localizer.ApplyHint(kf, HintNear(truth[40], 0.6, -0.5, 0.14));
  std::printf("[ hint ] %s after %d registrations, fitness %.2f, error %.3f m\n",
              ToString(out.verdict), out.registrations, out.check.fitness,
              PositionError(localizer, kf, truth[40]));
  EXPECT_EQ(out.verdict, HintVerdict::kTracking);
  EXPECT_TRUE(localizer.localized());
  EXPECT_LT(PositionError(localizer, kf, truth[40]), 0.05);
  EXPECT_LT((out.p_map - truth[40].translation()).norm(), 0.05);
  // It keeps tracking from there.
  for (size_t k = 41; k < 60; ++k) {
    const KeyframeCloud next = KeyframeAt(scene, truth[k], static_cast<int64_t>(k));
    localizer.AddKeyframe(next);
    EXPECT_LT(PositionError(localizer, next, truth[k]), 0.05) << "keyframe " << k;
  }
  EXPECT_TRUE(localizer.localized());
}

// Where every place has a look-alike 20 m away, relocalization without a hint waits
// (map_localizer_test.cpp); the hint picks the place, and the next keyframes confirm it.
TEST(MapLocalizerHint, AHintPicksTheRightBayAmongLookAlikes) {
  const Scene scene = test::PeriodicYard(5);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  for (const size_t start : {10, 150}) {
    MapLocalizer localizer(test::BoxYardMap(scene, 2, 1'000'000), LocalizationConfig{});
    const KeyframeCloud kf = KeyframeAt(scene, truth[start], static_cast<int64_t>(start));
    const HintOutcome out = localizer.ApplyHint(kf, HintNear(truth[start], -0.4, 0.3, -0.1));
    std::printf("[ hint ] periodic yard, start %zu: %s\n", start, ToString(out.verdict));
    ASSERT_TRUE(out.verdict == HintVerdict::kTracking || out.verdict == HintVerdict::kConfirming)
        << ToString(out.verdict);
    for (size_t k = start + 1; k < start + 6; ++k) {
      const KeyframeCloud next = KeyframeAt(scene, truth[k], static_cast<int64_t>(k));
      localizer.AddKeyframe(next);
      if (localizer.localized()) {
        EXPECT_LT(PositionError(localizer, next, truth[k]), 0.1) << "keyframe " << k;
      }
    }
    EXPECT_TRUE(localizer.localized()) << "start " << start;
  }
}

TEST(MapLocalizerHint, AHintThirtyMetresOffIsRefusedAndChangesNothing) {
  const Scene scene = test::BoxYard(7);
  MapLocalizer localizer(test::BoxYardMap(scene, 2, 1'000'000), LocalizationConfig{});
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  // Not localized yet: refused, still relocalizing.
  const KeyframeCloud kf = KeyframeAt(scene, truth[40], 40);
  const HintOutcome wrong = localizer.ApplyHint(kf, HintNear(truth[40], -30.0, 0.0, 0.0));
  std::printf("[ hint ] 30 m off: %s, best fitness %.2f (%s)\n", ToString(wrong.verdict),
              wrong.check.fitness, ToString(wrong.check.verdict));
  EXPECT_TRUE(wrong.verdict == HintVerdict::kNoFit || wrong.verdict == HintVerdict::kElsewhere)
      << ToString(wrong.verdict);
  EXPECT_EQ(localizer.state(), LocalizationState::kRelocalizing);
  EXPECT_EQ(localizer.stats().hints_refused, 1u);
  // Localized (by a good hint): a wrong one is refused and the correction stays.
  ASSERT_EQ(localizer.ApplyHint(kf, HintNear(truth[40], 0.2, 0.2, 0.0)).verdict,
            HintVerdict::kTracking);
  const Eigen::Isometry3d before = localizer.T_map_odom();
  const HintOutcome again = localizer.ApplyHint(kf, HintNear(truth[40], 0.0, 30.0, 0.5));
  EXPECT_TRUE(again.verdict == HintVerdict::kNoFit || again.verdict == HintVerdict::kElsewhere ||
              again.verdict == HintVerdict::kNoMap)
      << ToString(again.verdict);
  EXPECT_TRUE(localizer.localized());
  EXPECT_TRUE(localizer.T_map_odom().isApprox(before));
}

TEST(MapLocalizerHint, AHintOffTheMapIsRefusedAsNoMap) {
  const Scene scene = test::BoxYard(7);
  MapLocalizer localizer(test::BoxYardMap(scene, 2, 1'000'000), LocalizationConfig{});
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  const HintOutcome out =
      localizer.ApplyHint(KeyframeAt(scene, truth[0], 0), HintNear(truth[0], 500.0, 0.0, 0.0));
  EXPECT_EQ(out.verdict, HintVerdict::kNoMap);
  EXPECT_GT(out.nearest_node_m, 400.0);
  EXPECT_EQ(out.registrations, 0);
}

}  // namespace
}  // namespace swlio::estimator

// Localization in a saved map (issue 8) on the synthetic box yard: a map made from keyframes
// at the true poses, then a second drive whose odometry lives in another frame (its own start),
// seen from the true poses. Checks relocalization without any guess, its accuracy, that a map
// of another place never localizes, that tracking survives a changed scene, and that a lost
// pose is found again.
#include "swlio/estimator/map/map_localizer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "box_yard.h"
#include "box_yard_map.h"
#include "swlio/estimator/loop/keyframe_descriptor.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using test::BoxYard;
using test::Cut;
using test::Pose;
using test::RectangleDrive;
using test::Scene;

/// A map node every `every` poses of the rectangle drive, at its true pose (map = world).
SavedMap MakeMap(const Scene& scene, size_t every) {
  return test::BoxYardMap(scene, every, 1'000'000);
}

/// The second drive's odometry frame: where it started, turned and shifted from the map's.
const Eigen::Isometry3d kOdomFromWorld = Pose({-31.0, 12.0, 0.0}, 1.2);

/// A keyframe of the second drive: the sensor at the truth, the odometry in its own frame.
KeyframeCloud KeyframeAt(const Scene& scene, const Eigen::Isometry3d& truth, int64_t t_ns) {
  KeyframeCloud kf = Cut(scene, t_ns, truth);
  kf.T_world_imu = kOdomFromWorld * truth;
  return kf;
}

double PositionError(const MapLocalizer& l, const KeyframeCloud& kf, const Eigen::Isometry3d& T) {
  return ((l.T_map_odom() * kf.T_world_imu).translation() - T.translation()).norm();
}

TEST(MapLocalizer, RelocalizesWithoutAGuessAndTracks) {
  const Scene scene = BoxYard(7);
  MapLocalizer localizer(MakeMap(scene, 2), LocalizationConfig{});
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  int64_t localized_at = -1;
  double max_error_m = 0.0;
  for (size_t k = 37; k < 37 + 60; ++k) {  // from the middle of the first long side
    const KeyframeCloud kf = KeyframeAt(scene, truth[k % truth.size()], static_cast<int64_t>(k));
    localizer.AddKeyframe(kf);
    if (!localizer.localized()) continue;
    if (localized_at < 0) localized_at = static_cast<int64_t>(k - 37);
    max_error_m = std::max(max_error_m, PositionError(localizer, kf, truth[k % truth.size()]));
  }
  const LocalizationStats& s = localizer.stats();
  std::printf(
      "[ loc ] localized after %lld keyframes; %zu hypotheses, %zu tracked, max error "
      "%.3f m\n",
      static_cast<long long>(localized_at), s.hypotheses, s.tracked, max_error_m);
  ASSERT_GE(localized_at, 0);
  EXPECT_LE(localized_at, 3);  // a hypothesis and two confirmations
  EXPECT_LT(max_error_m, 0.05);
  const Eigen::Isometry3d T_map_odom_true = kOdomFromWorld.inverse();
  EXPECT_LT((localizer.T_map_odom().translation() - T_map_odom_true.translation()).norm(), 0.05);
  EXPECT_LT(
      Eigen::AngleAxisd(localizer.T_map_odom().linear().transpose() * T_map_odom_true.linear())
          .angle(),
      0.01);
}

TEST(MapLocalizer, NeverLocalizesInTheMapOfAnotherPlace) {
  MapLocalizer localizer(MakeMap(BoxYard(7), 2), LocalizationConfig{});
  const Scene elsewhere = BoxYard(8);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  for (size_t k = 0; k < truth.size(); k += 26) {  // 5 places around the yard
    localizer.AddKeyframe(KeyframeAt(elsewhere, truth[k], static_cast<int64_t>(k)));
    EXPECT_FALSE(localizer.localized()) << "keyframe " << k;
  }
  EXPECT_GT(localizer.stats().relocalization_registrations, 0u);
}

// Two look-alike bays: the boxes of the first 20 m of the yard repeat in the next 20 m.
// Starting in either bay, heading either way, a keyframe is either not yet localized or
// localized at the right place, never at the other bay (which would add 20 m to the APE); and
// it does localize once the drive reaches a corner that tells them apart.
TEST(MapLocalizer, NeverLocalizesAtALookAlikeBay) {
  const test::Scene scene = test::TwinBayYard(3);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  size_t localized = 0;
  // On the south side, in the first bay and in the second; on the north side (driving west),
  // in the second bay and in the first.
  for (const size_t start : {16, 56, 146, 186}) {
    MapLocalizer localizer(MakeMap(scene, 2), LocalizationConfig{});
    for (size_t k = start; k < start + 40; k += 3) {
      const Eigen::Isometry3d& T = truth[k % truth.size()];
      const KeyframeCloud kf = KeyframeAt(scene, T, static_cast<int64_t>(k));
      localizer.AddKeyframe(kf);
      if (!localizer.localized()) continue;
      ++localized;
      EXPECT_LT(PositionError(localizer, kf, T), 0.1) << "start " << start << ", keyframe " << k;
    }
    std::printf("[ loc ] twin bays, start %zu: %zu hypotheses (%zu dropped), %zu ambiguous\n",
                start, localizer.stats().hypotheses, localizer.stats().hypotheses_dropped,
                localizer.stats().ambiguous);
    EXPECT_TRUE(localizer.localized()) << "start " << start;
  }
  EXPECT_GT(localized, 0u);
}

/// Keyframes localized more than 1 m off on the yard whose boxes repeat every 20 m, from
/// x = 8 m to 19 m on its south side, on a day when a truck that stood at x = 32 m at mapping
/// time stands at x = 12 m.
size_t LocalizationsAtTheLookAlike(const LocalizationConfig& config) {
  const auto with_truck = [](double x) {
    Scene s = test::PeriodicYard(5);
    test::AddBox(Vec3(x - 4.5, -5.7, 0.0), Vec3(x + 4.5, -3.2, 3.5), 0.35, &s.planes, &s.edges);
    return s;
  };
  const Scene mapped = with_truck(32.0), today = with_truck(12.0);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  MapLocalizer localizer(MakeMap(mapped, 2), config);
  size_t wrong = 0;
  for (size_t k = 16; k < 40; k += 2) {
    const KeyframeCloud kf = KeyframeAt(today, truth[k], static_cast<int64_t>(k));
    localizer.AddKeyframe(kf);
    if (localizer.localized() && PositionError(localizer, kf, truth[k]) > 1.0) ++wrong;
  }
  return wrong;
}

// Vehicles move between patrols. Where the map has a truck at the look-alike place and today it
// stands at the same spot of the true one, the look-alike fits better than the true place: here
// by more than 0.05 and less than 0.10 (a 9 × 2.5 × 3.5 m truck). The margin must cover what a
// changed scene costs the true place: at 0.05 `revisit` seed 2 in `field` 1's map took a bay 56 m
// away for 65 s, and this yard's look-alike 20 m away is taken and tracked.
TEST(MapLocalizer, NeverLocalizesAtALookAlikeWhereATruckWasParked) {
  const size_t wrong_now = LocalizationsAtTheLookAlike(LocalizationConfig{});
  LocalizationConfig narrow;
  narrow.relocalize_min_margin = 0.05;
  const size_t wrong = LocalizationsAtTheLookAlike(narrow);
  std::printf(
      "[ loc ] truck moved between look-alikes: keyframes localized at the look-alike "
      "%zu at margin %.2f, %zu at 0.05\n",
      wrong_now, LocalizationConfig{}.relocalize_min_margin, wrong);
  EXPECT_EQ(wrong_now, 0u);
  EXPECT_GT(wrong, 0u);  // the look-alike does win at the old margin
}

/// Keyframes localized at the wrong place (more than 1 m off) on the long sides of a yard
/// whose boxes repeat every 20 m, from two starts.
size_t FalseLocalizations(const LocalizationConfig& config, size_t* localized) {
  const test::Scene scene = test::PeriodicYard(5);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  size_t wrong = 0;
  for (const size_t start : {10, 150}) {
    MapLocalizer localizer(MakeMap(scene, 2), config);
    for (size_t k = start; k < start + 30; k += 5) {
      const KeyframeCloud kf = KeyframeAt(scene, truth[k], static_cast<int64_t>(k));
      localizer.AddKeyframe(kf);
      if (localizer.localized()) {
        ++*localized;
        wrong += PositionError(localizer, kf, truth[k]) > 1.0 ? 1 : 0;
      }
    }
  }
  return wrong;
}

// Where no view tells two places apart (fitness differences of sampling noise), the localizer
// waits (ambiguous) rather than commit to the best fit, which a localizer without the margin
// does, right here only by luck.
TEST(MapLocalizer, WaitsWhereEveryPlaceHasALookAlike) {
  size_t localized = 0;
  EXPECT_EQ(FalseLocalizations(LocalizationConfig{}, &localized), 0u);
  EXPECT_EQ(localized, 0u);
  LocalizationConfig guessing;
  guessing.relocalize_min_margin = 0.0;
  guessing.confirmations = 0;
  size_t guessed = 0;
  const size_t wrong = FalseLocalizations(guessing, &guessed);
  std::printf("[ loc ] periodic yard: %zu keyframes localized; guessing: %zu, %zu wrong\n",
              localized, guessed, wrong);
  EXPECT_GT(guessed, 0u);  // the look-alikes do pass verification: only the margin stops them
}

// On a stretch where every place has a look-alike, relocalization is tried once per
// relocalize_every_m (0.9 m: every second keyframe, 0.5 m apart), not on every keyframe: each try
// verifies several places, and a daemon trying every keyframe falls behind.
TEST(MapLocalizer, ThrottlesRelocalizationWhileAmbiguous) {
  const test::Scene scene = test::PeriodicYard(5);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  LocalizationConfig config;
  config.relocalize_every_m = 0.9;
  MapLocalizer localizer(MakeMap(scene, 2), config);
  for (size_t k = 10; k < 20; ++k)
    localizer.AddKeyframe(KeyframeAt(scene, truth[k], static_cast<int64_t>(k)));
  const LocalizationStats& s = localizer.stats();
  std::printf(
      "[ loc ] ambiguous stretch: %zu keyframes, %zu tries, %zu deferred, %zu registrations\n",
      s.keyframes, s.relocalization_tries, s.relocalization_deferred,
      s.relocalization_registrations);
  EXPECT_FALSE(localizer.localized());
  EXPECT_EQ(s.relocalization_tries, 5u);
  EXPECT_EQ(s.relocalization_deferred, 5u);
  EXPECT_LE(s.relocalization_registrations, 5u * static_cast<size_t>(config.relocalize_candidates));
}

TEST(MapLocalizer, KeepsTrackingWhereTheSceneChanged) {
  const Scene mapped = BoxYard(7);
  MapLocalizer localizer(MakeMap(mapped, 2), LocalizationConfig{});
  // Since mapping: new containers along the first long side (about a third of what a
  // keyframe there sees), and every fifth mapped point gone.
  Scene changed;
  for (size_t i = 0; i < mapped.planes.size(); ++i)
    if (i % 5 != 0) changed.planes.push_back(mapped.planes[i]);
  changed.edges = mapped.edges;
  for (double x = 4.0; x < 36.0; x += 8.0) {
    test::AddBox(Vec3(x, 3.5, 0.0), Vec3(x + 5.0, 6.0, 2.6), 0.35, &changed.planes, &changed.edges);
  }
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  double max_error_m = 0.0;
  size_t localized = 0;
  for (size_t k = 100; k < 100 + truth.size(); ++k) {  // from the far side, into the change
    const Eigen::Isometry3d& T = truth[k % truth.size()];
    const KeyframeCloud kf = KeyframeAt(changed, T, static_cast<int64_t>(k));
    localizer.AddKeyframe(kf);
    if (!localizer.localized()) continue;
    ++localized;
    max_error_m = std::max(max_error_m, PositionError(localizer, kf, T));
  }
  std::printf(
      "[ loc ] changed scene: %zu of %zu keyframes localized, %zu track failures, max "
      "error %.3f m\n",
      localized, truth.size(), localizer.stats().track_failures, max_error_m);
  EXPECT_GT(localized, truth.size() * 9 / 10);
  EXPECT_EQ(localizer.stats().lost, 0u);
  EXPECT_LT(max_error_m, 0.1);
}

TEST(MapLocalizer, FindsALostPoseAgain) {
  const Scene scene = BoxYard(7);
  LocalizationConfig config;
  config.lost_after_failures = 3;
  MapLocalizer localizer(MakeMap(scene, 2), config);
  const std::vector<Eigen::Isometry3d> truth = RectangleDrive(0.0);
  for (size_t k = 0; k < 20; ++k)
    localizer.AddKeyframe(KeyframeAt(scene, truth[k], static_cast<int64_t>(k)));
  ASSERT_TRUE(localizer.localized());
  // The odometry jumps 4 m sideways (a wheel slip it did not see): tracking fails until the
  // pose is declared lost, then relocalization finds it again.
  const Eigen::Isometry3d slip = Pose({0.0, 4.0, 0.0}, 0.0);
  bool relocalized = false;
  for (size_t k = 20; k < 60; ++k) {
    KeyframeCloud kf = KeyframeAt(scene, truth[k], static_cast<int64_t>(k));
    kf.T_world_imu = slip * kf.T_world_imu;
    localizer.AddKeyframe(kf);
    if (localizer.stats().lost > 0 && localizer.localized()) {
      relocalized = true;
      EXPECT_LT(PositionError(localizer, kf, truth[k]), 0.05);
    }
  }
  EXPECT_EQ(localizer.stats().lost, 1u);
  EXPECT_TRUE(relocalized);
}

TEST(LocalizationConfig, DefaultsAreValidAndErrorsNamed) {
  EXPECT_TRUE(LocalizationConfig{}.Validate().empty());
  LocalizationConfig c;
  c.track_min_fitness = 1.5;
  c.relocalize_candidates = 0;
  c.relocalize_every_m = -1.0;
  const ConfigIssues issues = c.Validate();
  ASSERT_EQ(issues.size(), 3u);
  EXPECT_EQ(issues[0].key, "relocalize_candidates");
  EXPECT_EQ(issues[1].key, "relocalize_every_m");
  EXPECT_EQ(issues[2].key, "track_min_fitness");
}

}  // namespace
}  // namespace swlio::estimator

// VisibilityImage: a keyframe's free space tests map points (seen through, confirmed, unknown).
// Hand-made sweeps of a 16-ring sensor (synthetic_scan.h: −15°…+15° in 2° steps) around a
// level LiDAR 1 m above flat ground.

#include "swlio/estimator/map/visibility_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "swlio/estimator/loop/keyframe_store.h"
#include "swlio/estimator/registration/voxel_map.h"
#include "synthetic_scan.h"

namespace swlio::estimator {
namespace {

using test::At;
using test::kDegToRad;

constexpr double kHeightM = 1.0;  ///< the LiDAR above the ground

/// Every column of every ring: ground where a beam goes down, else a wall all around at
/// `wall_m` (a cylinder), and in the columns [c0, c1) an object at `object_m` (0: none).
std::vector<LidarPoint> Sweep(double wall_m, int c0 = 0, int c1 = 0, double object_m = 0.0) {
  std::vector<LidarPoint> points;
  for (int ring = 0; ring < 16; ++ring) {
    const double elevation = (-15.0 + 2.0 * ring) * kDegToRad;
    for (int column = 0; column < 1800; ++column) {
      double range = wall_m / std::cos(elevation);
      if (elevation < 0.0) range = std::min(range, kHeightM / std::sin(-elevation));
      if (object_m > 0.0 && column >= c0 && column < c1) range = std::min(range, object_m);
      points.push_back(At(ring, column, range));
    }
  }
  return points;
}

/// The world point at `range_m` along the beam of `ring` through `column`'s centre, moved by
/// `elevation_off_deg` up (the LiDAR at the world origin, level).
Eigen::Vector3d Along(int ring, int column, double range_m, double elevation_off_deg = 0.0) {
  const double azimuth = (column + 0.5) / 1800.0 * 2.0 * M_PI - M_PI;
  const double e = (-15.0 + 2.0 * ring + elevation_off_deg) * kDegToRad;
  return range_m * Eigen::Vector3d(std::cos(e) * std::cos(azimuth),
                                   -std::cos(e) * std::sin(azimuth), std::sin(e));
}

VisibilityImage Image(const std::vector<LidarPoint>& points) {
  VisibilityImage image{VisibilityConfig{}};
  image.Build(points, Eigen::Isometry3d::Identity());
  return image;
}

TEST(VisibilityImage, APointWhereTheBeamWentOnIsSeenThrough) {
  const VisibilityImage image = Image(Sweep(20.0));
  // A person's point 6 m away on a level beam, the wall 20 m behind it.
  EXPECT_EQ(image.Test(Along(8, 900, 6.0)), Visibility::kSeenThrough);
  EXPECT_EQ(image.Test(Along(8, 900, 19.9)), Visibility::kConfirmed) << "the wall itself";
  EXPECT_EQ(image.Test(Along(8, 900, 25.0)), Visibility::kUnknown) << "behind the wall";
  EXPECT_EQ(image.Test(Along(8, 900, 6.0, 1.0)), Visibility::kUnknown) << "between two beams";
}

TEST(VisibilityImage, AnObjectInFrontHidesThePointAndItsEdgeIsNotSeenThrough) {
  // An object 5 m away over columns [890, 910): what lies behind it is unknown, and so is a
  // point of its own at its edge, where the next column sees the wall.
  const VisibilityImage image = Image(Sweep(20.0, 890, 910, 5.0));
  EXPECT_EQ(image.Test(Along(8, 900, 10.0)), Visibility::kUnknown);
  EXPECT_EQ(image.Test(Along(8, 900, 5.0)), Visibility::kConfirmed);
  EXPECT_EQ(image.Test(Along(8, 909, 5.0)), Visibility::kConfirmed);
  EXPECT_EQ(image.Test(Along(8, 911, 5.0)), Visibility::kConfirmed) << "one column beside";
}

TEST(VisibilityImage, GroundAtGrazingIncidenceIsNotSeenThrough) {
  const VisibilityImage image = Image(Sweep(60.0));
  // The −3° beam (ring 6) meets the ground 19.1 m away, the −1° beam (ring 7) 57.3 m away;
  // ground points a little nearer lie within the beam tolerance (0.1 m) below those beams,
  // which land metres beyond them: no evidence of free space.
  for (const double range_m : {17.5, 18.0, 52.0, 53.0}) {
    const Eigen::Vector3d ground(range_m, 0.0, -kHeightM);
    EXPECT_NE(image.Test(ground), Visibility::kSeenThrough) << range_m << " m";
  }
  // The −5° beam meets the ground at 11.5 m; a ground point 0.05° above its line there is the
  // ground, not free space. A person's knee 6 m out on that beam is free space.
  EXPECT_NE(image.Test(Along(5, 450, 11.3, 0.05)), Visibility::kSeenThrough);
  EXPECT_EQ(image.Test(Along(5, 450, 6.0)), Visibility::kSeenThrough);
}

TEST(VisibilityImage, NoReturnIsNoEvidence) {
  std::vector<LidarPoint> points = Sweep(20.0);
  std::erase_if(points, [](const LidarPoint& p) { return p.ring == 8; });
  const VisibilityImage image = Image(points);
  EXPECT_EQ(image.Test(Along(8, 900, 6.0)), Visibility::kUnknown);
}

TEST(VisibilityImage, ScoresCountSeenThroughInARowAndAConfirmationResets) {
  int8_t s = 0;
  s = UpdateScore(s, Visibility::kSeenThrough);
  s = UpdateScore(s, Visibility::kUnknown);
  EXPECT_EQ(UpdateScore(s, Visibility::kSeenThrough), 2);
  EXPECT_EQ(UpdateScore(s, Visibility::kConfirmed), 0);
}

TEST(VisibilityImage, VoxelMapAndKeyframeStoreDropWhatIsSeenThroughTwice) {
  const VisibilityImage image = Image(Sweep(20.0));
  const Eigen::Vector3d person = Along(8, 900, 6.0), wall = Along(8, 900, 19.9);
  VoxelMap map(VoxelMapConfig{.voxel_m = 0.5, .max_points_per_voxel = 10});
  map.Insert({person, wall});
  const auto test = [&image](const Eigen::Vector3d& p) { return image.Test(p); };
  EXPECT_EQ(map.VoteAndRemove(Eigen::Vector3d::Zero(), 40.0, 2, test), 0u);
  const uint64_t revision = map.revision();
  EXPECT_EQ(map.VoteAndRemove(Eigen::Vector3d::Zero(), 40.0, 2, test), 1u);
  EXPECT_NE(map.revision(), revision);
  ASSERT_EQ(map.size(), 1u);
  EXPECT_EQ(map.Points().front(), wall);
  EXPECT_EQ(map.VoteAndRemove(Eigen::Vector3d(100, 0, 0), 40.0, 2, test), 0u) << "out of reach";

  KeyframeStore store;
  KeyframeCloud kf;
  kf.planes_lidar = {wall, person};
  kf.edges_lidar = {person};
  store.Add(kf, true);
  const auto test_f = [&image](const Eigen::Vector3f& p) { return image.Test(p.cast<double>()); };
  EXPECT_EQ(store.VoteAndRemove(0, 2, test_f), 0u);
  EXPECT_EQ(store.VoteAndRemove(0, 2, test_f), 2u);
  EXPECT_EQ(store.Planes(0, Eigen::Isometry3d::Identity()).size(), 1u);
  EXPECT_TRUE(store.Edges(0, Eigen::Isometry3d::Identity()).empty());
}

TEST(VisibilityConfig, ValidateNamesTheBadKeys) {
  EXPECT_TRUE(VisibilityConfig{}.Validate().empty());
  VisibilityConfig c;
  c.votes_to_remove = 0;
  c.margin_m = -1.0;
  c.max_range_m = 0.5;
  const ConfigIssues issues = c.Validate();
  ASSERT_EQ(issues.size(), 4u);
  EXPECT_EQ(issues[0].key, "max_range_m");  // below 1 m
  EXPECT_EQ(issues[1].key, "max_range_m");  // not beyond min_range_m
  EXPECT_EQ(issues[2].key, "margin_m");
  EXPECT_EQ(issues[3].key, "votes_to_remove");
}

}  // namespace
}  // namespace swlio::estimator

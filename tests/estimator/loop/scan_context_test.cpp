// Scan Context descriptor (Kim & Kim, IROS 2018): binning, yaw convention, distances, ring
// key, gravity alignment, database search and config validation.
#include "swlio/estimator/loop/scan_context.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace swlio::estimator {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kSectorRad = 6.0 * kDeg;  // default config: 60 sectors
constexpr double kSensorHeightM = 1.8;     // the ground is at z = −1.8 in the sensor frame

using Points = std::vector<Eigen::Vector3d>;

Eigen::Matrix3d Rz(double yaw_rad) {
  return Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// Angle a − b wrapped to (−π, π].
double AngleDiff(double a, double b) {
  double d = std::remainder(a - b, 2.0 * kPi);
  if (d <= -kPi) d += 2.0 * kPi;
  return d;
}

/// A point at the centre of sector `sector` (60 sectors) at horizontal range `range_m`.
Eigen::Vector3d AtSectorCentre(int sector, double range_m, double z_m) {
  const double azimuth = -kPi + (sector + 0.5) * kSectorRad;
  return {range_m * std::cos(azimuth), range_m * std::sin(azimuth), z_m};
}

/// A random town: boxes of random footprint and height (surfaces sampled), a long wall on one
/// side (asymmetric), and ground out to 25 m. Fixed seed: deterministic.
Points Scene(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Points points;
  const double ground_z = -kSensorHeightM;
  for (int i = 0; i < 40; ++i) {
    const double range = 4.0 + 50.0 * u(rng);
    const double azimuth = 2.0 * kPi * u(rng);
    const Eigen::Vector2d centre(range * std::cos(azimuth), range * std::sin(azimuth));
    const Eigen::Vector2d half(0.5 + 2.0 * u(rng), 0.5 + 2.0 * u(rng));
    const double top = ground_z + 0.5 + 8.0 * u(rng);
    const int n = static_cast<int>(100.0 * (half.x() + half.y()) * (top - ground_z));
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d xy = centre + Eigen::Vector2d(half.x() * (2.0 * u(rng) - 1.0),
                                                          half.y() * (2.0 * u(rng) - 1.0));
      const double z = k % 4 == 0 ? top : ground_z + (top - ground_z) * u(rng);
      points.emplace_back(xy.x(), xy.y(), z);
    }
  }
  for (int k = 0; k < 3000; ++k) {  // wall along y = 8 m, x from −5 to 35 m, 3 m high
    points.emplace_back(-5.0 + 40.0 * u(rng), 8.0, ground_z + 3.0 * u(rng));
  }
  for (int k = 0; k < 20000; ++k) {
    const double r = 25.0 * std::sqrt(u(rng));
    const double a = 2.0 * kPi * u(rng);
    points.emplace_back(r * std::cos(a), r * std::sin(a), ground_z + 0.02 * u(rng));
  }
  return points;
}

/// p' = R·p + t for every point.
Points Transformed(const Points& points, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Points out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(R * p + t);
  return out;
}

size_t NonZeroCells(const ScanContext& sc) {
  return static_cast<size_t>(
      std::count_if(sc.cells.begin(), sc.cells.end(), [](float v) { return v > 0.0f; }));
}

TEST(ScanContextBins, HandPlacedPointsLandInTheirBins) {
  const ScanContextConfig config;  // 20 rings of 3 m, 60 sectors of 6°, 1–60 m, offset 2 m
  const Points points = {
      AtSectorCentre(5, 10.0, 1.0),   // ring 3, sector 5: 3.0
      AtSectorCentre(5, 11.0, 0.5),   // same bin, lower: the max stays 3.0
      AtSectorCentre(10, 4.0, -1.5),  // ring 1, sector 10: 0.5
      AtSectorCentre(59, 59.9, 0.0),  // ring 19, sector 59: 2.0
      AtSectorCentre(0, 1.5, 0.25),   // ring 0, sector 0: 2.25
      AtSectorCentre(20, 7.0, -3.0),  // ring 2, sector 20: below the offset, clamps to 0
      AtSectorCentre(30, 0.5, 1.0),   // inside min_range_m: ignored
      {0.0, 60.0, 1.0},               // at max_range_m: ignored
      AtSectorCentre(32, 75.0, 1.0),  // beyond: ignored
      {-10.0, 0.0, 0.0},              // azimuth +π: the last sector (59), ring 3: 2.0
      {kPi, 0.0, std::nan("")},       // not finite: ignored
  };
  const ScanContext sc = MakeScanContext(config, points);
  ASSERT_EQ(sc.rings, 20);
  ASSERT_EQ(sc.sectors, 60);
  ASSERT_EQ(sc.cells.size(), 1200u);
  EXPECT_FLOAT_EQ(sc.at(3, 5), 3.0f);
  EXPECT_FLOAT_EQ(sc.at(1, 10), 0.5f);
  EXPECT_FLOAT_EQ(sc.at(19, 59), 2.0f);
  EXPECT_FLOAT_EQ(sc.at(0, 0), 2.25f);
  EXPECT_FLOAT_EQ(sc.at(2, 20), 0.0f);
  EXPECT_FLOAT_EQ(sc.at(3, 59), 2.0f);
  EXPECT_EQ(NonZeroCells(sc), 5u);
  ASSERT_EQ(sc.ring_key.size(), 20u);
  EXPECT_FLOAT_EQ(sc.ring_key[3], 2.0f / 60.0f);
  EXPECT_FLOAT_EQ(sc.ring_key[2], 0.0f);  // the clamped bin reads as empty
  EXPECT_FLOAT_EQ(sc.ring_key[19], 1.0f / 60.0f);
  EXPECT_FLOAT_EQ(sc.ring_key[10], 0.0f);
}

TEST(ScanContextBins, LidarFrameOverloadAppliesTheTransform) {
  const ScanContextConfig config;
  Eigen::Isometry3d T_gravity_lidar = Eigen::Isometry3d::Identity();
  T_gravity_lidar.linear() = Rz(0.7) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).matrix();
  T_gravity_lidar.translation() = Eigen::Vector3d(0.3, -0.2, 0.5);
  const Points points_gravity = Scene(1);
  const Points points_lidar = Transformed(points_gravity, T_gravity_lidar.inverse().linear(),
                                          T_gravity_lidar.inverse().translation());
  const ScanContext expected = MakeScanContext(config, points_gravity);
  const ScanContext sc = MakeScanContext(config, T_gravity_lidar, points_lidar);
  ASSERT_EQ(sc.cells.size(), expected.cells.size());
  size_t differing = 0;  // a point within rounding of a bin edge may change bin
  for (size_t i = 0; i < sc.cells.size(); ++i) {
    differing += std::abs(sc.cells[i] - expected.cells[i]) > 1e-4f ? 1 : 0;
  }
  EXPECT_LE(differing, 2u);
  EXPECT_GT(NonZeroCells(sc), 300u);
}

TEST(ScanContextBins, FromCellsRecomputesTheRingKey) {
  const ScanContext sc = MakeScanContext(ScanContextConfig{}, Scene(2));
  const ScanContext copy = ScanContextFromCells(sc.rings, sc.sectors, sc.cells);
  EXPECT_EQ(copy.cells, sc.cells);
  EXPECT_EQ(copy.ring_key, sc.ring_key);
}

// The convention of the header: the sensor turned by +θ (points seen as Rz(−θ)·p) compared with
// the unturned descriptor gives yaw_rad ≈ θ, and Rz(yaw_rad)·p' ≈ p.
TEST(ScanContextCompare, YawRecoversTheSensorRotation) {
  const ScanContextConfig config;
  const Points scene = Scene(3);
  const ScanContext a = MakeScanContext(config, scene);
  for (const double theta_deg : {30.0, -45.0, 90.0, 137.5, -100.7, 200.0, 350.0, 3.0}) {
    SCOPED_TRACE(theta_deg);
    const double theta = theta_deg * kDeg;
    const Points turned = Transformed(scene, Rz(-theta), Eigen::Vector3d::Zero());
    const ScanContext b = MakeScanContext(config, turned);
    const ScanContextMatch m = CompareScanContexts(b, a);
    EXPECT_LE(std::abs(AngleDiff(m.yaw_rad, theta)), kSectorRad);
    EXPECT_GT(m.yaw_rad, -kPi);
    EXPECT_LE(m.yaw_rad, kPi);
    EXPECT_LT(m.distance, config.max_distance);
    for (size_t i = 0; i < scene.size(); i += 997) {
      const double tolerance = scene[i].head<2>().norm() * kSectorRad + 1e-9;
      EXPECT_LE((Rz(m.yaw_rad) * turned[i] - scene[i]).norm(), tolerance);
    }
  }
}

TEST(ScanContextCompare, WholeSectorTurnIsAnExactShift) {
  const ScanContextConfig config;
  const Points scene = Scene(4);
  const ScanContext a = MakeScanContext(config, scene);
  const ScanContext b = MakeScanContext(config, Transformed(scene, Rz(-48.0 * kDeg), {0, 0, 0}));
  const ScanContextMatch m = CompareScanContexts(b, a);
  EXPECT_EQ(m.shift, 8);
  EXPECT_NEAR(m.yaw_rad, 48.0 * kDeg, 1e-9);
  EXPECT_NEAR(m.distance, 0.0, 1e-5);
}

TEST(ScanContextCompare, IdenticalDescriptorsAreAtZero) {
  const ScanContext a = MakeScanContext(ScanContextConfig{}, Scene(5));
  const ScanContextMatch m = CompareScanContexts(a, a);
  EXPECT_NEAR(m.distance, 0.0, 1e-6);
  EXPECT_EQ(m.shift, 0);
  EXPECT_EQ(m.yaw_rad, 0.0);
}

TEST(ScanContextCompare, SlightlyTranslatedCopyIsClose) {
  const ScanContextConfig config;
  const Points scene = Scene(6);
  const ScanContext a = MakeScanContext(config, scene);
  for (const Eigen::Vector3d& t : {Eigen::Vector3d(0.5, 0.0, 0.0), Eigen::Vector3d(0.0, -0.5, 0.0),
                                   Eigen::Vector3d(0.35, 0.35, 0.0)}) {
    const ScanContext b =
        MakeScanContext(config, Transformed(scene, Eigen::Matrix3d::Identity(), t));
    const ScanContextMatch m = CompareScanContexts(b, a);
    EXPECT_LT(m.distance, 0.5 * config.max_distance) << t.transpose();
    EXPECT_LE(std::abs(m.yaw_rad), kSectorRad) << t.transpose();
  }
}

TEST(ScanContextCompare, DifferentScenesAreFar) {
  const ScanContextConfig config;
  const ScanContext a = MakeScanContext(config, Scene(7));
  for (const uint32_t seed : {8u, 9u, 10u}) {
    const ScanContext b = MakeScanContext(config, Scene(seed));
    EXPECT_GT(CompareScanContexts(b, a).distance, config.max_distance) << seed;
  }
}

TEST(ScanContextCompare, NothingComparableGivesOne) {
  const ScanContextConfig config;
  const ScanContext a = MakeScanContext(config, {AtSectorCentre(5, 10.0, 1.0)});
  const ScanContext empty = MakeScanContext(config, {});
  EXPECT_EQ(CompareScanContexts(a, empty).distance, 1.0);
  ScanContextConfig smaller;
  smaller.sectors = 30;
  const ScanContext other_size = MakeScanContext(smaller, {AtSectorCentre(5, 10.0, 1.0)});
  EXPECT_EQ(CompareScanContexts(a, other_size).distance, 1.0);
}

double RingKeyDistance(const ScanContext& x, const ScanContext& y) {
  double d2 = 0.0;
  for (size_t r = 0; r < x.ring_key.size(); ++r) {
    d2 += std::pow(static_cast<double>(x.ring_key[r] - y.ring_key[r]), 2);
  }
  return std::sqrt(d2);
}

// Whole-sector turns only move columns: the key is unchanged. Other turns re-split objects
// between sectors, which moves the key a little, far less than another place's key is away.
TEST(ScanContextRingKey, InvariantUnderRotation) {
  const ScanContextConfig config;
  const Points scene = Scene(11);
  const ScanContext a = MakeScanContext(config, scene);
  double nearest_other = 1e9;
  for (const uint32_t seed : {12u, 13u, 14u, 15u}) {
    nearest_other =
        std::min(nearest_other, RingKeyDistance(a, MakeScanContext(config, Scene(seed))));
  }
  for (const double theta_deg : {36.0, -90.0, 354.0, 123.4, 251.7, -2.9}) {
    const Points turned = Transformed(scene, Rz(theta_deg * kDeg), Eigen::Vector3d::Zero());
    const ScanContext b = MakeScanContext(config, turned);
    const bool whole_sectors = std::fmod(std::abs(theta_deg), 6.0) == 0.0;
    const double tolerance = whole_sectors ? 1e-6 : 0.5 * nearest_other;
    EXPECT_LE(RingKeyDistance(a, b), tolerance) << theta_deg;
  }
}

TEST(ScanContextGravity, RemovesRollAndPitchButKeepsHeading) {
  for (const Eigen::Vector3d& rpy :
       {Eigen::Vector3d(0.1, -0.2, 1.3), Eigen::Vector3d(-0.3, 0.25, -2.8),
        Eigen::Vector3d(0.0, 0.0, 0.9)}) {
    SCOPED_TRACE(rpy.transpose());
    const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
    const Eigen::Matrix3d R_world_body = Rz(rpy.z()) * tilt;
    const Eigen::Matrix3d R = GravityAlignedFromBody(R_world_body);
    EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    // z: the body vector that points up in the world points up in the result.
    const Eigen::Vector3d up_body = R_world_body.transpose() * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR((R * up_body - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-12);
    // x: the body's x axis lies in the x–z plane, pointing forward.
    const Eigen::Vector3d forward = R * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(forward.y(), 0.0, 1e-12);
    EXPECT_GT(forward.x(), 0.0);
    // Nothing of the yaw: the result equals the yaw-free tilt's.
    EXPECT_NEAR((R - GravityAlignedFromBody(tilt)).norm(), 0.0, 1e-12);
    // The world-frame vector in the result is the world vector turned by −yaw about z.
    EXPECT_NEAR((R * R_world_body.transpose() - Rz(-rpy.z())).norm(), 0.0, 1e-12);
  }
}

class ScanContextDatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (uint32_t seed = 20; seed < 28; ++seed) {
      scenes_.push_back(Scene(seed));
      db_.Add(MakeScanContext(config_, scenes_.back()));
    }
  }
  /// Scene `i` seen from 0.3 m away with the sensor turned by `yaw_rad`.
  ScanContext Revisit(size_t i, double yaw_rad) const {
    return MakeScanContext(config_,
                           Transformed(scenes_[i], Rz(-yaw_rad), Eigen::Vector3d(0.2, -0.2, 0.0)));
  }

  ScanContextConfig config_;
  ScanContextDatabase db_{config_};
  std::vector<Points> scenes_;
};

TEST_F(ScanContextDatabaseTest, FindsTheRevisitedPlace) {
  ASSERT_EQ(db_.size(), 8u);
  const auto results = db_.Query(Revisit(5, 70.0 * kDeg), 3, {});
  ASSERT_FALSE(results.empty());
  EXPECT_EQ(results.front().first, 5u);
  EXPECT_LE(std::abs(AngleDiff(results.front().second.yaw_rad, 70.0 * kDeg)), kSectorRad);
  for (size_t k = 1; k < results.size(); ++k) {
    EXPECT_LE(results[k - 1].second.distance, results[k].second.distance);
  }
}

TEST_F(ScanContextDatabaseTest, RespectsAllowed) {
  const ScanContext query = Revisit(5, -120.0 * kDeg);
  ASSERT_FALSE(db_.Query(query, 8, [](size_t) { return true; }).empty());
  const auto results = db_.Query(query, 8, [](size_t i) { return i != 5; });
  for (const auto& [index, match] : results) EXPECT_NE(index, 5u);
  EXPECT_TRUE(results.empty());
}

TEST_F(ScanContextDatabaseTest, ReturnsNothingAboveMaxDistance) {
  const ScanContext unknown = MakeScanContext(config_, Scene(99));
  EXPECT_TRUE(db_.Query(unknown, 8, {}).empty());
  ScanContextConfig permissive = config_;
  permissive.max_distance = 1.0;
  ScanContextDatabase accepting(permissive);
  for (size_t i = 0; i < db_.size(); ++i) accepting.Add(db_.at(i));
  EXPECT_FALSE(accepting.Query(unknown, 8, {}).empty());
}

TEST_F(ScanContextDatabaseTest, BestFirstAndCapped) {
  const size_t copy = db_.Add(MakeScanContext(config_, scenes_[2]));  // exact copy of place 2
  const auto results = db_.Query(MakeScanContext(config_, scenes_[2]), 1, {});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results.front().first, 2u);  // tie at distance 0: the lower index first
  const auto both = db_.Query(Revisit(2, 0.0), 5, {});
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0].first, 2u);
  EXPECT_EQ(both[1].first, copy);
  EXPECT_EQ(both[0].second.distance, both[1].second.distance);
}

TEST(ScanContextConfig, ValidateNamesTheBadKeys) {
  EXPECT_TRUE(ScanContextConfig{}.Validate().empty());
  auto keys = [](const ScanContextConfig& c) {
    std::vector<std::string> out;
    for (const auto& issue : c.Validate()) out.push_back(issue.key);
    return out;
  };
  ScanContextConfig c;
  c.rings = 0;
  c.sectors = 2;
  c.candidates = 0;
  c.max_distance = 0.0;
  EXPECT_EQ(keys(c), (std::vector<std::string>{"rings", "sectors", "candidates", "max_distance"}));
  c = ScanContextConfig{};
  c.max_range_m = 1.0;  // not above min_range_m
  EXPECT_EQ(keys(c), std::vector<std::string>{"max_range_m"});
  c = ScanContextConfig{};
  c.min_range_m = -1.0;
  c.height_offset_m = -0.5;
  c.max_distance = 1.5;
  EXPECT_EQ(keys(c), (std::vector<std::string>{"min_range_m", "height_offset_m", "max_distance"}));
  c = ScanContextConfig{};
  c.max_range_m = 0.0;
  EXPECT_EQ(keys(c), (std::vector<std::string>{"max_range_m", "max_range_m"}));
}

}  // namespace
}  // namespace swlio::estimator

#pragma once
/// @file
/// A synthetic scene for loop-closure tests: ground and boxes sampled as points (planes, and
/// the boxes' vertical edges), keyframe clouds cut from it around a pose, and a rectangular
/// drive through it. No ray casting: every surface point within range is "seen".

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "swlio/core/lie.h"
#include "swlio/estimator/common/keyframe_cloud.h"

namespace swlio::test {

using estimator::KeyframeCloud;
using Vec3 = Eigen::Vector3d;
using Points = std::vector<Vec3>;

inline Eigen::Isometry3d Pose(const Vec3& p, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::Exp(Vec3(0.0, 0.0, yaw));
  T.translation() = p;
  return T;
}

/// Points on the faces of an axis-aligned box standing on the ground (planes) and on its
/// vertical edges (edges).
inline void AddBox(const Vec3& lo, const Vec3& hi, double step, Points* planes, Points* edges) {
  for (double z = 0.0; z <= hi.z(); z += step) {
    for (double x = lo.x(); x <= hi.x(); x += step) {
      planes->emplace_back(x, lo.y(), z);
      planes->emplace_back(x, hi.y(), z);
    }
    for (double y = lo.y(); y <= hi.y(); y += step) {
      planes->emplace_back(lo.x(), y, z);
      planes->emplace_back(hi.x(), y, z);
    }
    for (const double x : {lo.x(), hi.x()})
      for (const double y : {lo.y(), hi.y()}) edges->emplace_back(x, y, z);
  }
}

struct Scene {
  Points planes, edges;  ///< world frame
};

inline void AddGround(double x0, double x1, double y0, double y1, Scene* s) {
  for (double x = x0; x <= x1; x += 0.7)
    for (double y = y0; y <= y1; y += 0.7) s->planes.emplace_back(x, y, 0.0);
}

/// Boxes scattered around a 40 × 25 m rectangle of road (kept 3 m clear of it).
inline Scene BoxYard(unsigned seed) {
  Scene s;
  AddGround(-15.0, 55.0, -15.0, 40.0, &s);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-12.0, 52.0), uy(-12.0, 37.0), size(1.0, 3.0),
      height(1.5, 4.0);
  int placed = 0;
  while (placed < 60) {
    const Vec3 c(ux(rng), uy(rng), 0.0);
    const bool on_x_road =
        (std::abs(c.y()) < 3.0 || std::abs(c.y() - 25.0) < 3.0) && c.x() > -3.0 && c.x() < 43.0;
    const bool on_y_road =
        (std::abs(c.x()) < 3.0 || std::abs(c.x() - 40.0) < 3.0) && c.y() > -3.0 && c.y() < 28.0;
    if (on_x_road || on_y_road) continue;
    const Vec3 half(size(rng) / 2, size(rng) / 2, 0.0);
    AddBox(c - half, c + half + Vec3(0.0, 0.0, height(rng)), 0.35, &s.planes, &s.edges);
    ++placed;
  }
  return s;
}

/// Two look-alike bays (issue 8): the boxes of x ∈ [0, 20] repeat in x ∈ [20, 40] (as a
/// substation repeats its bays), and different boxes stand beyond both short sides, so places
/// 20 m apart along the long sides look alike and the corners tell them apart.
inline Scene TwinBayYard(unsigned seed) {
  Scene s;
  AddGround(-15.0, 55.0, -15.0, 40.0, &s);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-12.0, 52.0), uy(-12.0, 37.0), size(1.0, 3.0),
      height(1.5, 4.0);
  int twins = 0, others = 0;
  while (twins < 12 || others < 12) {
    const Vec3 c(ux(rng), uy(rng), 0.0);
    const bool in_bay = c.x() > 3.0 && c.x() < 17.0;
    const bool outside = (c.x() > -12.0 && c.x() < -3.0) || (c.x() > 43.0 && c.x() < 52.0);
    const bool on_road = std::abs(c.y()) < 3.0 || std::abs(c.y() - 25.0) < 3.0;
    if (on_road || (!in_bay && !outside) || (in_bay && twins >= 12) || (outside && others >= 12))
      continue;
    const Vec3 half(size(rng) / 2, size(rng) / 2, 0.0);
    const Vec3 top(0.0, 0.0, height(rng));
    for (const double shift : in_bay ? std::vector<double>{0.0, 20.0} : std::vector<double>{0.0}) {
      const Vec3 o(shift, 0.0, 0.0);
      AddBox(c - half + o, c + half + o + top, 0.35, &s.planes, &s.edges);
    }
    ++(in_bay ? twins : others);
  }
  return s;
}

/// Boxes that repeat every 20 m along x over the whole yard (one tile, four times): every
/// place on the long sides has a look-alike 20 m away that no view within range tells apart.
inline Scene PeriodicYard(unsigned seed) {
  Scene s;
  AddGround(-15.0, 55.0, -15.0, 40.0, &s);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(3.0, 17.0), uy(-12.0, 37.0), size(1.0, 3.0),
      height(1.5, 4.0);
  for (int placed = 0; placed < 12;) {
    const Vec3 c(ux(rng), uy(rng), 0.0);
    if (std::abs(c.y()) < 3.0 || std::abs(c.y() - 25.0) < 3.0) continue;
    const Vec3 half(size(rng) / 2, size(rng) / 2, 0.0);
    const Vec3 top(0.0, 0.0, height(rng));
    for (const double shift : {-20.0, 0.0, 20.0, 40.0}) {
      const Vec3 o(shift, 0.0, 0.0);
      AddBox(c - half + o, c + half + o + top, 0.35, &s.planes, &s.edges);
    }
    ++placed;
  }
  return s;
}

/// Two parallel walls 6 m apart along x, on ground: nothing fixes x.
inline Scene Corridor() {
  Scene s;
  AddGround(-40.0, 40.0, -3.0, 3.0, &s);
  for (double x = -40.0; x <= 40.0; x += 0.35)
    for (double z = 0.0; z <= 3.0; z += 0.35) {
      s.planes.emplace_back(x, -3.0, z);
      s.planes.emplace_back(x, 3.0, z);
    }
  return s;
}

inline const Eigen::Isometry3d kImuLidar = Pose({0.1, 0.0, 0.3}, 0.0);

/// What the LiDAR at `T_world_imu` sees: scene points within 20 m, in its own frame.
inline KeyframeCloud Cut(const Scene& s, int64_t t_ns, const Eigen::Isometry3d& T_world_imu) {
  KeyframeCloud kf;
  kf.t_ns = t_ns;
  kf.T_imu_lidar = kImuLidar;
  const Eigen::Isometry3d T_lidar_world = (T_world_imu * kImuLidar).inverse();
  for (const auto& [in, out] :
       {std::pair{&s.planes, &kf.planes_lidar}, {&s.edges, &kf.edges_lidar}}) {
    for (const Vec3& p : *in) {
      const Vec3 q = T_lidar_world * p;
      if (q.norm() < 20.0) out->push_back(q);
    }
  }
  return kf;
}

/// The true IMU poses (0.5 m apart, the IMU 0.5 m above ground) around the rectangle and on
/// for `extra_m` past the start.
inline std::vector<Eigen::Isometry3d> RectangleDrive(double extra_m) {
  std::vector<Eigen::Isometry3d> out;
  const Vec3 corners[] = {{0, 0, 0.5}, {40, 0, 0.5}, {40, 25, 0.5}, {0, 25, 0.5}, {0, 0, 0.5}};
  for (int side = 0; side < 4; ++side) {
    const Vec3 d = (corners[side + 1] - corners[side]).normalized();
    const double yaw = std::atan2(d.y(), d.x());
    const double length = (corners[side + 1] - corners[side]).norm();
    for (double s = 0.0; s < length; s += 0.5) out.push_back(Pose(corners[side] + s * d, yaw));
  }
  for (double s = 0.0; s <= extra_m; s += 0.5) out.push_back(Pose(Vec3(s, 0.0, 0.5), 0.0));
  return out;
}

}  // namespace swlio::test

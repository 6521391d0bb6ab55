#pragma once
/// @file
/// Test helper: moving objects injected into simulated sweeps, with their own labels, until the
/// simulator has actors of its own. A mover is a vertical box (a person, a car) on a straight
/// path between two times, standing on the terrain; a return whose ray from the LiDAR (at its
/// firing time) meets a box present then, before the static surface, is moved onto the box and
/// labelled with the box. Rays that hit nothing are not in the sweep, so a box seen only
/// against the sky is missing from it (the upper half of a near person): the test's boxes are
/// smaller than the simulator's actors will be, not larger.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"
#include "swlio/core/time.h"

namespace swlio::test {

struct MovingBox {
  Eigen::Vector3d half_m = Eigen::Vector3d(0.25, 0.25, 0.9);  ///< a person
  double t0_s = 0.0, t1_s = 0.0;  ///< present in [t0, t1], moving from xy0 to xy1
  Eigen::Vector2d xy0 = Eigen::Vector2d::Zero(), xy1 = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;

  bool Present(double t_s) const { return t_s >= t0_s && t_s <= t1_s; }
  Eigen::Vector2d Centre(double t_s) const {
    const double a = t1_s > t0_s ? (t_s - t0_s) / (t1_s - t0_s) : 0.0;
    return xy0 + a * (xy1 - xy0);
  }
};

/// Distance along the unit ray (o, d) to the box `b` at `t_s` (its bottom on the terrain at its
/// centre), or +inf.
inline double HitBox(const sim::SimSetup& setup,
                     const MovingBox& b,
                     double t_s,
                     const Eigen::Vector3d& o,
                     const Eigen::Vector3d& d) {
  const Eigen::Vector2d c = b.Centre(t_s);
  const Eigen::Vector3d centre(c.x(), c.y(), setup.world->terrain.Height(c) + b.half_m.z());
  const Eigen::Matrix3d R_box = Eigen::AngleAxisd(b.yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Vector3d ob = R_box.transpose() * (o - centre), db = R_box.transpose() * d;
  double t_in = 0.0, t_out = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(db[a]) < 1e-12) {
      if (std::abs(ob[a]) > b.half_m[a]) return std::numeric_limits<double>::infinity();
      continue;
    }
    double t0 = (-b.half_m[a] - ob[a]) / db[a], t1 = (b.half_m[a] - ob[a]) / db[a];
    if (t0 > t1) std::swap(t0, t1);
    t_in = std::max(t_in, t0);
    t_out = std::min(t_out, t1);
  }
  return t_in <= t_out && t_in > 0.0 ? t_in : std::numeric_limits<double>::infinity();
}

/// Puts the boxes into `ls` (points, true hit points); `mover[i]` is the box index + 1 of
/// point i, or 0 for the static world.
inline void InjectBoxes(const sim::SimSetup& setup,
                        const std::vector<MovingBox>& boxes,
                        sim::LabelledScan* ls,
                        std::vector<uint16_t>* mover) {
  mover->assign(ls->scan.points.size(), 0);
  const Eigen::Isometry3d T_end_world = ls->T_world_lidar_end.inverse();
  for (size_t i = 0; i < ls->scan.points.size(); ++i) {
    const double t_s = NsToSec(ls->scan.t_start_ns + ls->scan.points[i].dt_ns);
    bool any = false;
    for (const MovingBox& b : boxes) any = any || b.Present(t_s);
    if (!any) continue;
    const sim::Kinematics k = setup.trajectory->At(t_s);
    const Eigen::Vector3d o = k.p_world + k.R_world_body * setup.lidar.T_imu_lidar.translation();
    const Eigen::Vector3d to = ls->p_world[i] - o;
    const double range = to.norm();
    const Eigen::Vector3d d = to / range;
    double best = range;
    for (size_t j = 0; j < boxes.size(); ++j) {
      if (!boxes[j].Present(t_s)) continue;
      const double s = HitBox(setup, boxes[j], t_s, o, d);
      if (s < best) {
        best = s;
        (*mover)[i] = static_cast<uint16_t>(j + 1);
      }
    }
    if ((*mover)[i] == 0) continue;
    ls->p_world[i] = o + best * d;
    ls->scan.points[i].xyz_m = (T_end_world * ls->p_world[i]).cast<float>();
  }
}

/// Movers along the first seconds of a route, placed from the true trajectory: a person
/// crossing the road ahead, a car passing the other way, a car parked beside the road that
/// drives off once the robot has passed, and a person walking along beside the robot.
inline std::vector<MovingBox> RouteMovers(const sim::SimSetup& setup, double t0_s) {
  const auto at = [&](double t_s, double ahead_m, double left_m) {
    const sim::Kinematics k = setup.trajectory->At(t_s);
    const Eigen::Vector3d fwd = k.R_world_body.col(0), left = k.R_world_body.col(1);
    const Eigen::Vector3d p = k.p_world + ahead_m * fwd + left_m * left;
    return Eigen::Vector2d(p.x(), p.y());
  };
  const auto yaw = [&](double t_s) {
    const Eigen::Vector3d fwd = setup.trajectory->At(t_s).R_world_body.col(0);
    return std::atan2(fwd.y(), fwd.x());
  };
  std::vector<MovingBox> boxes;
  // A person crossing 8 m ahead at 1.3 m/s, from 5 m left to 5 m right.
  boxes.push_back({{0.25, 0.25, 0.9},
                   t0_s + 2.0,
                   t0_s + 2.0 + 10.0 / 1.3,
                   at(t0_s + 2.0, 8, 5),
                   at(t0_s + 2.0, 8, -5),
                   yaw(t0_s + 2.0)});
  // A car passing the other way at 5 m/s, 3 m to the left.
  boxes.push_back({{2.2, 0.9, 0.75},
                   t0_s + 6.0,
                   t0_s + 14.0,
                   at(t0_s + 6.0, 25, 3.5),
                   at(t0_s + 6.0, -15, 3.5),
                   yaw(t0_s + 6.0)});
  // A car parked 4 m to the right, 6 m ahead, that leaves 3 s after the robot passed it.
  const Eigen::Vector2d parked = at(t0_s, 6, -4.5);
  boxes.push_back({{2.2, 0.9, 0.75}, t0_s - 60.0, t0_s + 9.0, parked, parked, yaw(t0_s)});
  // A person walking beside the robot, 3 m to the left, at its own pace, for 8 s.
  boxes.push_back({{0.25, 0.25, 0.9},
                   t0_s + 12.0,
                   t0_s + 20.0,
                   at(t0_s + 12.0, 3, 3),
                   at(t0_s + 20.0, 3, 3),
                   yaw(t0_s + 12.0)});
  return boxes;
}

}  // namespace swlio::test

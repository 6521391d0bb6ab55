#include "disturb/actor_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swlio::sim {
namespace {

constexpr double kPersonMarginM = 0.15;
constexpr double kVehicleMarginM = 0.3;
constexpr double kActorMarginM = 0.2;

/// Projected half length of `f` on unit axis `u`.
double Radius(const Footprint& f, const Eigen::Vector2d& u) {
  const Eigen::Vector2d ax(std::cos(f.yaw_rad), std::sin(f.yaw_rad));
  const Eigen::Vector2d ay(-ax.y(), ax.x());
  return f.half_m.x() * std::abs(ax.dot(u)) + f.half_m.y() * std::abs(ay.dot(u));
}

/// Bounds of the ground an actor can cover: its waypoints grown by its radius.
void PathBounds(const Actor& a, double grow_m, Eigen::Vector2d* lo, Eigen::Vector2d* hi) {
  *lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  *hi = -*lo;
  for (const Eigen::Vector2d& w : a.plan().waypoints_xy) {
    *lo = lo->cwiseMin(w);
    *hi = hi->cwiseMax(w);
  }
  *lo -= Eigen::Vector2d::Constant(a.radius_m() + grow_m);
  *hi += Eigen::Vector2d::Constant(a.radius_m() + grow_m);
}

bool BoundsOverlap(const Eigen::Vector2d& lo_a,
                   const Eigen::Vector2d& hi_a,
                   const Eigen::Vector2d& lo_b,
                   const Eigen::Vector2d& hi_b) {
  return (lo_a.array() <= hi_b.array()).all() && (lo_b.array() <= hi_a.array()).all();
}

/// Times at which to look at a moving actor: its start, every `step` of its motion, its end.
std::vector<double> MotionSamples(const Actor& a, double step_s) {
  std::vector<double> t = {a.plan().t_go_s};
  if (!std::isfinite(a.plan().t_go_s)) return {0.0};
  for (double s = a.plan().t_go_s; s < a.EndS(); s += step_s) t.push_back(s);
  t.push_back(a.EndS());
  return t;
}

}  // namespace

Footprint FootprintAt(const Actor& actor, const ActorPose& pose, double margin_m) {
  const ActorPart& b = actor.bounds();
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  Footprint f;
  f.center_m = pose.ground_m.head<2>() + Eigen::Vector2d(c * b.center_m.x() - s * b.center_m.y(),
                                                         s * b.center_m.x() + c * b.center_m.y());
  f.half_m = b.half_m.head<2>() + Eigen::Vector2d::Constant(margin_m);
  f.yaw_rad = pose.yaw_rad;
  return f;
}

bool Overlap(const Footprint& a, const Footprint& b) {
  const Eigen::Vector2d d = b.center_m - a.center_m;
  for (const double yaw : {a.yaw_rad, b.yaw_rad}) {
    for (const Eigen::Vector2d& u : {Eigen::Vector2d(std::cos(yaw), std::sin(yaw)),
                                     Eigen::Vector2d(-std::sin(yaw), std::cos(yaw))}) {
      if (std::abs(d.dot(u)) > Radius(a, u) + Radius(b, u)) return false;  // separating axis
    }
  }
  return true;
}

double Distance(const Eigen::Vector2d& p, const Footprint& f) {
  const Eigen::Vector2d r = p - f.center_m;
  const double c = std::cos(f.yaw_rad), s = std::sin(f.yaw_rad);
  const Eigen::Vector2d local(c * r.x() + s * r.y(), -s * r.x() + c * r.y());
  return (local.cwiseAbs() - f.half_m).cwiseMax(0.0).norm();
}

RobotTrack SampleRobot(const Trajectory& trajectory, double dt_s) {
  RobotTrack track;
  track.dt_s = dt_s;
  for (int64_t k = 0; static_cast<double>(k) * dt_s <= trajectory.duration_s(); ++k) {
    track.xy.push_back(trajectory.At(static_cast<double>(k) * dt_s).p_world.head<2>());
  }
  return track;
}

double MinRobotDistanceM(const Actor& actor, const RobotTrack& robot, double* at_s) {
  Eigen::Vector2d lo, hi;
  PathBounds(actor, 0.0, &lo, &hi);
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < robot.xy.size(); ++k) {
    const Eigen::Vector2d& p = robot.xy[k];
    // Far from every place the actor can be: no nearer than the bounds.
    const double bound = (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
    if (bound >= best) continue;
    const double t = static_cast<double>(k) * robot.dt_s;
    const double d = Distance(p, FootprintAt(actor, actor.At(t)));
    if (d < best) {
      best = d;
      if (at_s != nullptr) *at_s = t;
    }
  }
  return best;
}

ActorClearance::ActorClearance(const World* world, const RobotTrack* robot)
    : world_(world), robot_(robot) {
  for (const Primitive& p : world->primitives()) {
    Obstacle o{p.min_xy, p.max_xy, 0.0, 0.0};
    switch (p.kind) {
      case Primitive::Kind::kBox:
        o.z_min = p.box.center.z() - p.box.half_m.z();
        o.z_max = p.box.center.z() + p.box.half_m.z();
        break;
      case Primitive::Kind::kCylinder:
        o.z_min = std::min(p.cylinder.a.z(), p.cylinder.b.z()) - p.cylinder.radius_m;
        o.z_max = std::max(p.cylinder.a.z(), p.cylinder.b.z()) + p.cylinder.radius_m;
        break;
      case Primitive::Kind::kSphere:
        o.z_min = p.sphere.center.z() - p.sphere.radius_m;
        o.z_max = p.sphere.center.z() + p.sphere.radius_m;
        break;
    }
    obstacles_.push_back(o);
  }
}

bool ActorClearance::ClearOfWorld(const Actor& actor) const {
  const bool person = actor.plan().kind == ActorKind::kPerson;
  const double margin = person ? kPersonMarginM : kVehicleMarginM;
  Eigen::Vector2d lo, hi;
  PathBounds(actor, margin, &lo, &hi);
  std::vector<const Obstacle*> near;
  for (const Obstacle& o : obstacles_) {
    if (BoundsOverlap(lo, hi, o.min_xy, o.max_xy)) near.push_back(&o);
  }
  const double step_s =
      std::min(0.25 / actor.plan().cruise_mps, 0.1 / actor.plan().turn_rate_radps);
  const ActorPart& b = actor.bounds();
  for (const double t : MotionSamples(actor, step_s)) {
    const ActorPose pose = actor.At(t);
    const Footprint f = FootprintAt(actor, pose, margin);
    const double z_lo = pose.ground_m.z() + 0.05;  // what stands on the ground is an obstacle
    const double z_hi = pose.ground_m.z() + b.center_m.z() + b.half_m.z() + margin;
    for (const Obstacle* o : near) {
      if (o->z_max < z_lo || o->z_min > z_hi) continue;
      Footprint box;
      box.center_m = 0.5 * (o->min_xy + o->max_xy);
      box.half_m = 0.5 * (o->max_xy - o->min_xy);
      if (Overlap(f, box)) return false;
    }
  }
  return true;
}

bool ActorClearance::ClearOfRobot(const Actor& actor) const {
  return MinRobotDistanceM(actor, *robot_) >= kRobotClearanceM;
}

bool ActorClearance::ClearOfActors(const Actor& actor, const ActorSet& set) const {
  Eigen::Vector2d lo, hi;
  PathBounds(actor, kActorMarginM, &lo, &hi);
  const double drive_s = set.drive_duration_s();
  for (const Actor& other : set.actors()) {
    Eigen::Vector2d olo, ohi;
    PathBounds(other, kActorMarginM, &olo, &ohi);
    if (!BoundsOverlap(lo, hi, olo, ohi)) continue;
    // Both stand before the first starts and after the last stops: those two instants cover
    // the standing times; every 0.1 s between them.
    const double t0 = std::clamp(std::min(actor.plan().t_go_s, other.plan().t_go_s), 0.0, drive_s);
    const double t1 = std::clamp(std::max(actor.EndS(), other.EndS()), t0, drive_s);
    for (double t = t0;; t = std::min(t + 0.1, t1)) {
      if (Overlap(FootprintAt(actor, actor.At(t), kActorMarginM),
                  FootprintAt(other, other.At(t), kActorMarginM))) {
        return false;
      }
      if (t >= t1) break;
    }
  }
  return true;
}

}  // namespace swlio::sim

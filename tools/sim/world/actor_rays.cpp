#include "world/actor_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swlio::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Horizontal spread of the beams around the packet's wedge: a ±15° beam of a LiDAR tilted by a
/// few degrees (mounting, terrain) points a little off its azimuth.
constexpr double kWedgeMarginRad = 3.0 * 3.14159265358979323846 / 180.0;

double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

double IntersectPart(const ActorPart& part, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  double t0 = -kInf, t1 = kInf;
  for (int i = 0; i < 3; ++i) {
    const double rel = o(i) - part.center_m(i);
    if (std::abs(d(i)) < 1e-12) {
      if (std::abs(rel) > part.half_m(i)) return kInf;
      continue;
    }
    double ta = (-part.half_m(i) - rel) / d(i);
    double tb = (part.half_m(i) - rel) / d(i);
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return kInf;
  }
  return t0 > 1e-6 ? t0 : kInf;
}

void ActorRays::BeginPacket(const ActorSet& set,
                            double t0_s,
                            double t1_s,
                            const Eigen::Vector3d& origin_m,
                            const Eigen::Vector2d& dir_first_xy,
                            const Eigen::Vector2d& dir_last_xy,
                            double max_range_m) {
  set_ = &set;
  picked_.clear();
  const Eigen::Vector2d mid = (dir_first_xy + dir_last_xy).normalized();
  const double half_wedge =
      0.5 * std::atan2(std::abs(Cross2(dir_first_xy, dir_last_xy)), dir_first_xy.dot(dir_last_xy));
  const double t_mid = 0.5 * (t0_s + t1_s);
  for (const Actor& a : set.actors()) {
    const ActorPose pose = a.At(t_mid);
    // Sphere around the body, grown by the way it can go in half a packet.
    const double r = a.radius_m() + pose.speed_mps * 0.5 * (t1_s - t0_s) + 0.05;
    const Eigen::Vector3d c = pose.ground_m + Eigen::Vector3d(0, 0, a.bounds().center_m.z());
    const Eigen::Vector2d to = (c - origin_m).head<2>();
    const double dist = to.norm();
    if ((c - origin_m).norm() - r > max_range_m) continue;
    if (dist > r) {
      const double off = std::atan2(std::abs(Cross2(mid, to)), mid.dot(to));
      if (off > half_wedge + std::asin(r / dist) + kWedgeMarginRad) continue;
    }
    picked_.push_back(
        {&a, set.Moving(a.id()), pose.ground_m, std::cos(pose.yaw_rad), std::sin(pose.yaw_rad)});
  }
}

void ActorRays::SetTime(double t_s) {
  for (Picked& p : picked_) {
    const ActorPose pose = p.actor->At(t_s);
    p.ground_m = pose.ground_m;
    p.cos_yaw = std::cos(pose.yaw_rad);
    p.sin_yaw = std::sin(pose.yaw_rad);
  }
}

void ActorRays::Cast(const Eigen::Vector3d& o,
                     const Eigen::Vector3d& d,
                     double max_range_m,
                     RayHit* hit,
                     uint16_t* actor,
                     bool* moving) const {
  *actor = 0;
  double best = hit->range_m > 0.0 ? hit->range_m : max_range_m;
  for (const Picked& p : picked_) {
    const Eigen::Vector3d r = o - p.ground_m;  // into the actor's frame: rotate by −yaw
    const Eigen::Vector3d ol(p.cos_yaw * r.x() + p.sin_yaw * r.y(),
                             -p.sin_yaw * r.x() + p.cos_yaw * r.y(), r.z());
    const Eigen::Vector3d dl(p.cos_yaw * d.x() + p.sin_yaw * d.y(),
                             -p.sin_yaw * d.x() + p.cos_yaw * d.y(), d.z());
    for (const ActorPart& part : p.actor->plan().parts) {
      const double t = IntersectPart(part, ol, dl);
      if (t < best) {
        best = t;
        hit->range_m = t;
        hit->cls = p.actor->surface_class();
        hit->reflectivity = part.reflectivity;
        *actor = p.actor->id();
        *moving = p.moving;
      }
    }
  }
}

}  // namespace swlio::sim

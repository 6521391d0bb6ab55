#include "world/actors.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swlio::sim {
namespace {

/// a − b wrapped to (−π, π].
double AngleDiff(double a, double b) {
  double d = std::fmod(a - b, 2.0 * std::numbers::pi);
  if (d > std::numbers::pi) d -= 2.0 * std::numbers::pi;
  if (d <= -std::numbers::pi) d += 2.0 * std::numbers::pi;
  return d;
}

}  // namespace

const char* ActorKindName(ActorKind kind) {
  return kind == ActorKind::kPerson ? "person" : "vehicle";
}

Actor::Actor(uint16_t id, ActorPlan plan, const Terrain* terrain)
    : id_(id), plan_(std::move(plan)), terrain_(terrain) {
  plan_.stop_s.resize(plan_.waypoints_xy.size(), 0.0);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (const ActorPart& p : plan_.parts) {
    lo = lo.cwiseMin(p.center_m - p.half_m);
    hi = hi.cwiseMax(p.center_m + p.half_m);
    radius_m_ = std::max(radius_m_, (p.center_m.cwiseAbs() + p.half_m).norm());
  }
  bounds_.center_m = 0.5 * (lo + hi);
  bounds_.half_m = 0.5 * (hi - lo);
  bounds_.reflectivity = plan_.parts.empty() ? 0.0f : plan_.parts.front().reflectivity;
  BuildLegs();
}

void Actor::BuildLegs() {
  const auto& w = plan_.waypoints_xy;
  double t = plan_.t_go_s;
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    Leg leg;
    const Eigen::Vector2d d = w[i + 1] - w[i];
    leg.length_m = d.norm();
    leg.yaw_rad = std::atan2(d.y(), d.x());
    if (i > 0) {  // turn in place from the last leg's heading, then stand
      const double turn = std::abs(AngleDiff(leg.yaw_rad, legs_.back().yaw_rad));
      t += turn / plan_.turn_rate_radps + plan_.stop_s[i];
    }
    const double a = plan_.acc_mps2;
    leg.v_peak_mps = std::min(plan_.cruise_mps, std::sqrt(leg.length_m * a));
    leg.t_acc_s = leg.v_peak_mps / a;
    const double cruise_m = leg.length_m - leg.v_peak_mps * leg.t_acc_s;
    leg.duration_s = 2.0 * leg.t_acc_s + std::max(0.0, cruise_m) / leg.v_peak_mps;
    leg.t0_s = t;
    t += leg.duration_s;
    legs_.push_back(leg);
  }
}

double Actor::LegDistance(const Leg& leg, double tau_s, double* speed_mps) const {
  const double a = plan_.acc_mps2, v = leg.v_peak_mps, ta = leg.t_acc_s;
  if (tau_s <= ta) {
    *speed_mps = a * tau_s;
    return 0.5 * a * tau_s * tau_s;
  }
  const double t_brake = leg.duration_s - ta;
  if (tau_s <= t_brake) {
    *speed_mps = v;
    return 0.5 * v * ta + v * (tau_s - ta);
  }
  const double left = std::max(0.0, leg.duration_s - tau_s);
  *speed_mps = a * left;
  return leg.length_m - 0.5 * a * left * left;
}

ActorPose Actor::Standing(const Eigen::Vector2d& xy, double yaw_rad) const {
  return {Eigen::Vector3d(xy.x(), xy.y(), terrain_->Height(xy)), yaw_rad, 0.0};
}

ActorPose Actor::At(double t_s) const {
  const auto& w = plan_.waypoints_xy;
  if (legs_.empty()) return Standing(w.front(), plan_.yaw0_rad);
  if (t_s <= legs_.front().t0_s) return Standing(w.front(), legs_.front().yaw_rad);
  for (size_t i = 0; i < legs_.size(); ++i) {
    const Leg& leg = legs_[i];
    if (t_s < leg.t0_s) {  // at waypoint i: turning from the last leg's heading, then standing
      const double from = legs_[i - 1].yaw_rad;
      const double turn = AngleDiff(leg.yaw_rad, from);
      const double since = t_s - (legs_[i - 1].t0_s + legs_[i - 1].duration_s);
      const double frac =
          std::min(1.0, since * plan_.turn_rate_radps / std::max(1e-9, std::abs(turn)));
      return Standing(w[i], from + frac * turn);
    }
    if (t_s <= leg.t0_s + leg.duration_s) {
      ActorPose pose;
      const double s = LegDistance(leg, t_s - leg.t0_s, &pose.speed_mps);
      const Eigen::Vector2d xy = w[i] + (w[i + 1] - w[i]) * (s / leg.length_m);
      pose.ground_m = Eigen::Vector3d(xy.x(), xy.y(), terrain_->Height(xy));
      pose.yaw_rad = leg.yaw_rad;
      return pose;
    }
  }
  return Standing(w.back(), legs_.back().yaw_rad);
}

double Actor::ArrivalS(size_t k) const {
  if (k == 0 || legs_.empty()) return plan_.t_go_s;
  const Leg& leg = legs_[std::min(k, legs_.size()) - 1];
  return leg.t0_s + leg.duration_s;
}

double Actor::PassS(size_t leg_index, double dist_m) const {
  const Leg& leg = legs_.at(leg_index);
  const double a = plan_.acc_mps2;
  const double d = std::clamp(dist_m, 0.0, leg.length_m);
  const double d_acc = 0.5 * leg.v_peak_mps * leg.t_acc_s;
  double tau = 0.0;
  if (d <= d_acc) {
    tau = std::sqrt(2.0 * d / a);
  } else if (d <= leg.length_m - d_acc) {
    tau = leg.t_acc_s + (d - d_acc) / leg.v_peak_mps;
  } else {
    tau = leg.duration_s - std::sqrt(2.0 * (leg.length_m - d) / a);
  }
  return leg.t0_s + tau;
}

double Actor::EndS() const { return ArrivalS(legs_.size()); }

bool Actor::MovesWithin(double t0_s, double t1_s) const {
  return !legs_.empty() && plan_.t_go_s < t1_s && EndS() > t0_s;
}

SurfaceClass Actor::surface_class() const {
  return plan_.kind == ActorKind::kPerson ? SurfaceClass::kPerson : SurfaceClass::kVehicle;
}

ActorSet::ActorSet(const Terrain* terrain, double drive_duration_s)
    : terrain_(terrain), drive_duration_s_(drive_duration_s) {}

const Actor& ActorSet::Add(ActorPlan plan) {
  actors_.emplace_back(static_cast<uint16_t>(actors_.size() + 1), std::move(plan), terrain_);
  return actors_.back();
}

bool ActorSet::Moving(uint16_t id) const {
  return id >= 1 && id <= actors_.size() && Get(id).MovesWithin(0.0, drive_duration_s_);
}

}  // namespace swlio::sim

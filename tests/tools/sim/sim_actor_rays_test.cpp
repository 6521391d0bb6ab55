// ActorRays (world/actor_rays.h): picking the actors per packet wedge loses no hit that a cast
// against every actor finds, and the nearest part wins over a farther static hit.

#include "world/actor_rays.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace swlio::sim {
namespace {

ActorPlan Standing(ActorKind kind, Eigen::Vector2d xy, double yaw, Eigen::Vector3d half) {
  ActorPlan p;
  p.kind = kind;
  p.waypoints_xy = {xy};
  p.yaw0_rad = yaw;
  p.parts = {{Eigen::Vector3d(0, 0, half.z()), half, 50.0f}};
  return p;
}

/// Every actor, no picking: the nearest part along the ray at `t_s`.
double BruteForce(const ActorSet& set,
                  double t_s,
                  const Eigen::Vector3d& o,
                  const Eigen::Vector3d& d) {
  double best = std::numeric_limits<double>::infinity();
  for (const Actor& a : set.actors()) {
    const ActorPose pose = a.At(t_s);
    if (!pose.present) continue;
    const Eigen::Vector3d r = o - pose.ground_m;
    const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
    const Eigen::Vector3d ol(c * r.x() + s * r.y(), -s * r.x() + c * r.y(), r.z());
    const Eigen::Vector3d dl(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
    for (const ActorPart& part : a.plan().parts) best = std::min(best, IntersectPart(part, ol, dl));
  }
  return best;
}

TEST(SimActorRays, PickingLosesNoHit) {
  Terrain flat;
  ActorSet set(&flat, 100.0);
  const Eigen::Vector3d person(0.175, 0.25, 0.9), van(2.4, 0.95, 1.0);
  set.Add(Standing(ActorKind::kPerson, {1.2, 0.3}, 0.4, person));     // right beside the sensor
  set.Add(Standing(ActorKind::kVehicle, {6.0, -0.5}, 1.3, van));      // across azimuth 0
  set.Add(Standing(ActorKind::kPerson, {-40.0, 25.0}, 0.0, person));  // far
  set.Add(Standing(ActorKind::kVehicle, {-3.0, -9.0}, 2.0, van));
  ActorPlan walker = Standing(ActorKind::kPerson, {10.0, 10.0}, 0.0, person);
  walker.waypoints_xy.push_back({-10.0, 10.0});
  walker.t_go_s = 0.0;
  set.Add(walker);
  ActorPlan gone = Standing(ActorKind::kVehicle, {3.0, 3.0}, 0.0, van);
  gone.vanish_s = 0.0;  // left before the drive
  set.Add(gone);
  const Eigen::Vector3d origin(0.0, 0.0, 0.5);
  constexpr double kWedge = 4.8 * std::numbers::pi / 180.0;
  ActorRays rays;
  size_t hits = 0, checked = 0;
  for (double start = 0.0, t = 0.0; start < 2.0 * std::numbers::pi; start += kWedge, t += 0.2) {
    auto dir = [](double a) { return Eigen::Vector2d(std::cos(a), std::sin(a)); };
    rays.BeginPacket(set, t, t + 0.0013, origin, dir(start), dir(start + kWedge), 150.0);
    rays.SetTime(t);
    for (double a = start; a < start + kWedge; a += kWedge / 24.0) {
      for (double elev_deg = -15.0; elev_deg <= 15.0; elev_deg += 2.0) {
        const double e = elev_deg * std::numbers::pi / 180.0;
        const Eigen::Vector3d d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
        RayHit hit;  // nothing static
        uint16_t actor = 0;
        bool moving = false;
        rays.Cast(origin, d, 150.0, &hit, &actor, &moving);
        const double truth = BruteForce(set, t, origin, d);
        ++checked;
        if (!std::isfinite(truth)) {
          ASSERT_EQ(actor, 0) << "azimuth " << a;
          continue;
        }
        ASSERT_NE(actor, 0) << "missed at azimuth " << a << " elevation " << elev_deg;
        ASSERT_NE(actor, 6) << "not there";
        ASSERT_NEAR(hit.range_m, truth, 1e-9);
        EXPECT_EQ(moving, actor == 5);
        ++hits;
      }
    }
  }
  EXPECT_GT(hits, 500u);
  EXPECT_GT(checked, 10'000u);
}

TEST(SimActorRays, NearerStaticHitWins) {
  Terrain flat;
  ActorSet set(&flat, 10.0);
  set.Add(Standing(ActorKind::kVehicle, {10.0, 0.0}, 0.0, Eigen::Vector3d(2.4, 0.95, 1.0)));
  ActorRays rays;
  const Eigen::Vector3d o(0, 0, 0.5), d = Eigen::Vector3d::UnitX();
  rays.BeginPacket(set, 0.0, 0.0013, o, {1, -0.01}, {1, 0.01}, 150.0);
  rays.SetTime(0.0);
  RayHit wall{5.0, SurfaceClass::kWall, 60.0f};
  uint16_t actor = 9;
  bool moving = true;
  rays.Cast(o, d, 150.0, &wall, &actor, &moving);
  EXPECT_EQ(actor, 0);
  EXPECT_EQ(wall.cls, SurfaceClass::kWall);
  RayHit far{50.0, SurfaceClass::kWall, 60.0f};
  rays.Cast(o, d, 150.0, &far, &actor, &moving);
  EXPECT_EQ(actor, 1);
  EXPECT_FALSE(moving);
  EXPECT_EQ(far.cls, SurfaceClass::kVehicle);
  EXPECT_NEAR(far.range_m, 10.0 - 2.4, 1e-12);
}

}  // namespace
}  // namespace swlio::sim

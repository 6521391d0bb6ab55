#include "disturb/actor_roles.h"

#include <cmath>
#include <vector>

#include "world/substation.h"

namespace swlio::sim {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using L = Layout;

// Walking speed: MUTCD's design value is 1.2 m/s (TRR 2002, DOI 10.3141/2002-12, which finds
// normal walking slower than crossing); field observations in New Zealand give means of
// 80–95 m/min, 1.33–1.58 m/s. People here walk at 1.0–1.5 m/s (the range).
constexpr double kWalkMinMps = 1.0, kWalkMaxMps = 1.5;
/// Assumed: a walker reaches full speed within about two steps.
constexpr double kWalkAccMps2 = 0.7;
constexpr double kWalkTurnRadps = 1.5;
// Vehicles up to 5 m/s (18 km/h), the site speed limit (no published limit for a
// substation's yard was found); from 3 m/s. Assumed gentle acceleration and braking, and the
// yaw rate of a tight manoeuvre.
constexpr double kDriveMinMps = 3.0, kDriveMaxMps = 5.0;
constexpr double kDriveAccMps2 = 1.0;
constexpr double kDriveTurnRadps = 0.5;
/// Lane centre of a vehicle beside the robot (on the road's centre line): a 1.9 m vehicle
/// keeps 1.35 m from the robot's centre and stays within the 4 m kept clear.
constexpr double kLaneM = 2.3;

/// Upright body of 1.6–1.85 m (the issue's ~1.75 m), 0.5 m across the shoulders, 0.35 m deep,
/// sunk 5 cm into the ground (no gap on slopes); clothing reflectivity 20–60.
ActorPart PersonBody(Rng& rng) {
  const double h = rng.Uniform(1.6, 1.85);
  return {Vector3d(0, 0, 0.5 * (h - 0.05)), Vector3d(0.175, 0.25, 0.5 * (h + 0.05)),
          static_cast<float>(rng.Uniform(20.0, 60.0))};
}

/// A maintenance van (4.6–5.0 × 1.85–2.0 m, 1.9–2.1 m high, with the bonnet as a 0.9 m long
/// step 1.1 m high) or a pickup (bonnet, cab, bed 1.1 m high), painted 30–130 (dark to white),
/// the pickup's cab mostly glass (15–30).
std::vector<ActorPart> VehicleBody(Rng& rng) {
  const double len = rng.Uniform(4.6, 5.0), half_w = 0.5 * rng.Uniform(1.85, 2.0);
  const float paint = static_cast<float>(rng.Uniform(30.0, 130.0));
  auto part = [&](double x0, double x1, double h, float refl) {
    return ActorPart{Vector3d(0.5 * (x0 + x1), 0, 0.5 * (h - 0.05)),
                     Vector3d(0.5 * (x1 - x0), half_w, 0.5 * (h + 0.05)), refl};
  };
  const double front = 0.5 * len, back = -0.5 * len;
  if (rng.Uniform() < 0.6) {
    const double h = rng.Uniform(1.9, 2.1);
    return {part(back, front - 0.9, h, paint), part(front - 0.9, front, 1.1, paint)};
  }
  const float glass = static_cast<float>(rng.Uniform(15.0, 30.0));
  return {part(back, front - 2.9, 1.1, paint), part(front - 2.9, front - 1.0, 1.85, glass),
          part(front - 1.0, front, 1.1, paint)};
}

ActorPlan Person(ActorRole role, Rng& rng) {
  ActorPlan p;
  p.kind = ActorKind::kPerson;
  p.role = role;
  p.cruise_mps = rng.Uniform(kWalkMinMps, kWalkMaxMps);
  p.acc_mps2 = kWalkAccMps2;
  p.turn_rate_radps = kWalkTurnRadps;
  p.parts = {PersonBody(rng)};
  return p;
}

ActorPlan Vehicle(ActorRole role, Rng& rng) {
  ActorPlan p;
  p.kind = ActorKind::kVehicle;
  p.role = role;
  p.cruise_mps = rng.Uniform(kDriveMinMps, kDriveMaxMps);
  p.acc_mps2 = kDriveAccMps2;
  p.turn_rate_radps = kDriveTurnRadps;
  p.parts = VehicleBody(rng);
  return p;
}

void Add(ActorPlan* p, const Vector2d& xy, double stop_s = 0.0) {
  p->waypoints_xy.push_back(xy);
  p->stop_s.push_back(stop_s);
}

double Side(Rng& rng) { return rng.Uniform() < 0.5 ? -1.0 : 1.0; }

/// Crosses the robot's path where the robot is at the anchor time, 1.5–3.5 s before it gets
/// there: from 7–9 m on one side, a 1–3 s look at the road edge, on to 7–9 m on the other
/// side, maybe turning along it for a few metres.
ActorPlan Crossing(const RobotAnchor& a, Rng& rng) {
  ActorPlan p = Person(ActorRole::kCrossing, rng);
  const double s = Side(rng);
  const Vector2d c = a.xy;
  Add(&p, c + s * rng.Uniform(7.0, 9.0) * a.left);
  Add(&p, c + s * 3.2 * a.left, rng.Uniform(1.0, 3.0));
  const Vector2d far = c - s * rng.Uniform(7.0, 9.0) * a.left;
  Add(&p, far);
  const double along = rng.Uniform(-8.0, 8.0);
  if (std::abs(along) > 1.0) Add(&p, far + along * a.heading);
  TimeToPass(&p, 1, 3.2, a.t_s - rng.Uniform(1.5, 3.5));
  return p;
}

/// Walks along a road edge (2.9–3.3 m off the robot's line), towards the robot or with it, is
/// abreast of it at the anchor time, stops 4–15 m further for 3–12 s, walks on 5–20 m.
ActorPlan Walking(const RobotAnchor& a, Rng& rng) {
  ActorPlan p = Person(ActorRole::kWalking, rng);
  const Vector2d edge = a.xy + Side(rng) * rng.Uniform(2.9, 3.3) * a.left;
  const Vector2d dir = Side(rng) * a.heading;
  const double before = rng.Uniform(15.0, 30.0);
  Add(&p, edge - before * dir);
  const Vector2d stop = edge + rng.Uniform(4.0, 15.0) * dir;
  Add(&p, stop, rng.Uniform(3.0, 12.0));
  Add(&p, stop + rng.Uniform(5.0, 20.0) * dir);
  TimeToPass(&p, 0, before, a.t_s);
  return p;
}

/// Walks from the road edge into the lane between two bays (x = 76, 104, 132, 160 between the
/// south or north road and the trench covers of the middle road) 6–20 m deep, inspects there
/// for 15–45 s, walks back out and on along the road edge. Needs the robot on the south or
/// north road within 25 m of a lane.
std::optional<ActorPlan> Inspecting(const RobotAnchor& a, Rng& rng) {
  const double roads[] = {L::kRoadSouth, L::kRoadNorth};
  for (const double road_y : roads) {
    if (std::abs(a.xy.y() - road_y) > 2.0) continue;
    const double lane_x = 76.0 + 28.0 * std::round((a.xy.x() - 76.0) / 28.0);
    if (std::abs(lane_x - a.xy.x()) > 25.0 || lane_x < 76.0 || lane_x > 160.0) return std::nullopt;
    const double into = road_y == L::kRoadSouth ? 1.0 : -1.0;  // the bays' side
    ActorPlan p = Person(ActorRole::kInspecting, rng);
    const Vector2d mouth(lane_x, road_y + into * 3.1);
    const Vector2d ex = Vector2d::UnitX();
    Add(&p, mouth + Side(rng) * rng.Uniform(5.0, 15.0) * ex);
    Add(&p, mouth);
    Add(&p, mouth + into * rng.Uniform(6.0, 20.0) * Vector2d::UnitY(), rng.Uniform(15.0, 45.0));
    Add(&p, mouth);
    Add(&p, mouth + Side(rng) * rng.Uniform(5.0, 15.0) * ex);
    TimeToPass(&p, 0, (p.waypoints_xy[1] - p.waypoints_xy[0]).norm(),
               a.t_s - rng.Uniform(0.0, 10.0));
    return p;
  }
  return std::nullopt;
}

/// Meets the robot in the other lane (on its left: right-hand traffic, as in China, where the
/// world's origin lies): from 30–60 m ahead to 30–60 m behind, abreast of it at the anchor time;
/// half of them stop 3–10 s on the way (stop and go).
ActorPlan Oncoming(const RobotAnchor& a, Rng& rng) {
  ActorPlan p = Vehicle(ActorRole::kOncoming, rng);
  const Vector2d lane = a.xy + kLaneM * a.left;
  const double ahead = rng.Uniform(30.0, 60.0);
  Add(&p, lane + ahead * a.heading);
  if (rng.Uniform() < 0.5)
    Add(&p, lane + rng.Uniform(12.0, ahead - 8.0) * a.heading, rng.Uniform(3.0, 10.0));
  const Vector2d last = p.waypoints_xy.back();
  Add(&p, lane - rng.Uniform(30.0, 60.0) * a.heading);
  TimeToPass(&p, p.waypoints_xy.size() - 2, (last - lane).norm(), a.t_s);
  return p;
}

/// Passes the robot on its left at the anchor time, stops 15–30 m ahead of it for 8–25 s (the
/// robot passes it then), drives on 20–40 m.
ActorPlan Overtaking(const RobotAnchor& a, Rng& rng) {
  ActorPlan p = Vehicle(ActorRole::kOvertaking, rng);
  const Vector2d lane = a.xy + kLaneM * a.left;
  const double behind = rng.Uniform(25.0, 40.0);
  Add(&p, lane - behind * a.heading);
  const Vector2d stop = lane + rng.Uniform(15.0, 30.0) * a.heading;
  Add(&p, stop, rng.Uniform(8.0, 25.0));
  Add(&p, stop + rng.Uniform(20.0, 40.0) * a.heading);
  TimeToPass(&p, 0, behind, a.t_s);
  return p;
}

/// Parked beside the robot's road (2.6–3.0 m off its line, either side, along the road either
/// way) within 20 m of where the robot is at the anchor time.
ActorPlan Parked(ActorRole role, const RobotAnchor& a, Rng& rng) {
  ActorPlan p = Vehicle(role, rng);
  const double side = Side(rng);
  const Vector2d dir = side * a.heading;  // parked on the right of its own direction
  Add(&p, a.xy + rng.Uniform(-20.0, 20.0) * a.heading - side * rng.Uniform(2.6, 3.0) * a.left);
  p.yaw0_rad = std::atan2(dir.y(), dir.x());
  if (role == ActorRole::kParkedLeaving) {  // leaves 5 s before to 15 s after the anchor
    Add(&p, p.waypoints_xy.front() + rng.Uniform(40.0, 80.0) * dir);
    p.t_go_s = a.t_s + rng.Uniform(-5.0, 15.0);
  }
  return p;
}

}  // namespace

void TimeToPass(ActorPlan* plan, size_t leg, double dist_m, double t_s) {
  plan->t_go_s = 0.0;
  const Actor probe(1, *plan, nullptr);  // timing only: the terrain is not read
  plan->t_go_s = t_s - probe.PassS(leg, dist_m);
}

std::optional<ActorPlan> DrawPerson(ActorRole role, const RobotAnchor& anchor, Rng& rng) {
  switch (role) {
    case ActorRole::kCrossing:
      return Crossing(anchor, rng);
    case ActorRole::kWalking:
      return Walking(anchor, rng);
    case ActorRole::kInspecting:
      return Inspecting(anchor, rng);
    default:
      return std::nullopt;
  }
}

std::optional<ActorPlan> DrawVehicle(ActorRole role, const RobotAnchor& anchor, Rng& rng) {
  switch (role) {
    case ActorRole::kOncoming:
      return Oncoming(anchor, rng);
    case ActorRole::kOvertaking:
      return Overtaking(anchor, rng);
    case ActorRole::kParkedLeaving:
    case ActorRole::kParkedAllDrive:
      return Parked(role, anchor, rng);
    default:
      return std::nullopt;
  }
}

}  // namespace swlio::sim

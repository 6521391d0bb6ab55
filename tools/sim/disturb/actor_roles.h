#pragma once
/// @file
/// The parts people and vehicles play in a drive (ActorRole), each drawn around an anchor: a
/// time of the drive and where the robot is then, so that the robot meets them. Magnitudes and
/// their sources are in actor_roles.cpp and tools/sim/README.md ("Moving people and vehicles").

#include <Eigen/Core>
#include <optional>

#include "rng.h"
#include "world/actors.h"

namespace swlio::sim {

/// The robot at one time of the drive.
struct RobotAnchor {
  double t_s = 0.0;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  Eigen::Vector2d heading = Eigen::Vector2d::UnitX();  ///< unit, direction of travel
  Eigen::Vector2d left = Eigen::Vector2d::UnitY();     ///< unit, heading turned by +90°
};

/// A person of `role` (kCrossing, kWalking or kInspecting) placed and timed around `anchor`;
/// nothing when the role does not fit there (an inspection needs a bay lane nearby).
std::optional<ActorPlan> DrawPerson(ActorRole role, const RobotAnchor& anchor, Rng& rng);

/// A vehicle of `role` (kOncoming, kOvertaking, kParkedLeaving, kParkedAllDrive) placed and
/// timed around `anchor`.
std::optional<ActorPlan> DrawVehicle(ActorRole role, const RobotAnchor& anchor, Rng& rng);

/// Sets plan->t_go_s so that the actor is `dist_m` along leg `leg` at `t_s`.
void TimeToPass(ActorPlan* plan, size_t leg, double dist_m, double t_s);

}  // namespace swlio::sim

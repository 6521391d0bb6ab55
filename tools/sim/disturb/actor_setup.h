#pragma once
/// @file
/// The `people` and `vehicles` disturbances: actors drawn for a drive and added to its world
/// (World::actors), where the LiDAR simulator sees them.
///
/// Drawn from the drive's seed (SimSetup::seed), never the world's: `revisit --seed S
/// --world-seed W` is W's substation with S's people and vehicles, so that its parked vehicles
/// stand elsewhere than those of the mapping drive `field --seed W` (a day later). Each actor is
/// timed around the robot (anchor times spread over the drive) and kept only when it is clear
/// of the static world, the robot and the actors drawn before it (actor_clearance.h).

#include "scenarios/sim_setup.h"

namespace swlio::sim {

/// Number of people for a drive of `duration_s`: 2 up to 4 min, 8 for loop943 (950 s), at most 9.
int PeopleCount(double duration_s);
/// Number of vehicles: 2 up to 4 min, 5 for loop943, at most 6.
int VehicleCount(double duration_s);

void SetUpPeople(SimSetup* setup);
void SetUpVehicles(SimSetup* setup);

}  // namespace swlio::sim

#pragma once
/// @file
/// Plain CSV dumps of a world and a route, for pictures (scripts/plot_world.py) and checks.

#include <filesystem>
#include <string>

#include "scenarios/sim_setup.h"

namespace swlio::sim {

/// Writes DIR/world.csv (one primitive per line: kind,class,x,y,z,size1,size2,size3,yaw, with
/// box half sizes, cylinder end points, sphere radius) and DIR/route.csv (t_s,x,y,z,yaw_rad,
/// speed_mps at 10 Hz). Returns false with `error` on failure.
bool DumpWorldAndRoute(const SimSetup& setup, const std::filesystem::path& dir, std::string* error);

}  // namespace swlio::sim

#pragma once
/// @file
/// Built-in scenarios: each is fully determined by its name and a seed.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "disturb/disturbances.h"
#include "scenarios/trajectory.h"

namespace swlio::sim {

struct Scenario {
  std::string name;
  std::string description;
  RouteSpec route;
  /// Added to the substation's own (this scenario's course; the other scenarios' world is the
  /// same for every one of them).
  std::vector<Bump> extra_bumps;
  /// Field disturbances on by default (`field`: all of them); `--disturb` adds to them.
  DisturbanceSet disturb;
};

/// Names of the built-in scenarios: short, loop943, degenerate, aggressive, revisit,
/// calibration, field.
std::vector<std::string> ScenarioNames();

/// The scenario called `name`, or nothing when there is none. Only `revisit` depends on the
/// seed (its start place and direction).
std::optional<Scenario> MakeScenario(const std::string& name, uint64_t seed = 1);

}  // namespace swlio::sim

#pragma once
/// @file
/// Sets up the weather, edge and temperature disturbances in a SimSetup (mixed_pixels, rain,
/// dust, dropouts, temperature), drawing their random parts from the setup's seed, and writes
/// their truth into the manifest's `disturbances:` block.

#include <string>

#include "scenarios/sim_setup.h"

namespace swlio::sim {

void SetUpMixedPixels(SimSetup* setup);
void SetUpRain(SimSetup* setup);
/// Dust puffs while the robot drives: the drive's route and duration must be final.
void SetUpDust(SimSetup* setup);
void SetUpDropouts(SimSetup* setup);
void SetUpTemperature(SimSetup* setup);

/// The manifest lines (two-space indent, unique keys) of those that are on.
std::string WeatherManifestLines(const SimSetup& setup);

}  // namespace swlio::sim

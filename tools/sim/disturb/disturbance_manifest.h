#pragma once
/// @file
/// The manifest's `disturbances:` block: which field disturbances are on and the truth of each
/// model (what a test holds the estimator's estimates against). Keys are unique in the file.

#include <string>

#include "scenarios/sim_setup.h"

namespace swlio::sim {

/// "disturbances:\n  list: …\n  …" (always written; `list: none` when none is on).
std::string DisturbanceManifestBlock(const SimSetup& setup);

}  // namespace swlio::sim

#pragma once
/// @file
/// Turns disturbances on in a SimSetup: each sets up its model (drawn from the setup's seed
/// where the model has random parts) in the sensor or world it acts on. Call after
/// MakeSimSetup and before RepeatRoute or any emitter is built.

#include <cstdint>
#include <optional>

#include "disturb/disturbances.h"
#include "scenarios/sim_setup.h"

namespace swlio::sim {

/// What the command line can fix instead of drawing it from the seed.
struct DisturbanceOverrides {
  /// The LiDAR–IMU time offset (s): IMU samples are stamped this much later than they were
  /// measured (negative: earlier). Drawn in ±10 ms from the seed when not given.
  std::optional<double> time_offset_s;
  /// Chassis vibration's acceleration RMS (m/s²) standing and at 1 m/s; drawn from the seed in
  /// 0.5–1.0 and 1.0–2.0 when not given.
  std::optional<double> vibration_rest_rms_mps2;
  std::optional<double> vibration_drive_rms_mps2;
  /// Draws the vibration's tones (frequencies, axes, phases) from this seed instead of the
  /// drive's: the same drive shaken by another vibration of the same magnitude.
  std::optional<uint64_t> vibration_seed;
};

/// Adds `set` to setup->disturb and sets up each model that was not on yet.
void ApplyDisturbances(SimSetup* setup,
                       const DisturbanceSet& set,
                       const DisturbanceOverrides& overrides = {});

}  // namespace swlio::sim

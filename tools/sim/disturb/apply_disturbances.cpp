#include "disturb/apply_disturbances.h"

#include <memory>

#include "disturb/actor_setup.h"
#include "disturb/weather_setup.h"
#include "rng.h"
#include "scenarios/chassis_vibration.h"

namespace swlio::sim {
namespace {

/// Unknown time offsets of this size are what the issue asks the estimator to find: USB-serial
/// latency (an FTDI adapter's latency timer defaults to 16 ms, FTDI AN232B-04) and the IMU's
/// own filter delay (a few ms) are of that order, and nobody calibrated them.
constexpr double kMaxTimeOffsetS = 0.010;

void SetUpTimeOffset(SimSetup* setup, const DisturbanceOverrides& overrides) {
  Rng rng(setup->seed ^ 0x7D0FF5E7ull);
  const double drawn = rng.Uniform(-kMaxTimeOffsetS, kMaxTimeOffsetS);
  setup->imu.time_offset_s = overrides.time_offset_s.value_or(drawn);
}

/// Magnitudes: chassis_vibration.h.
void SetUpVibration(SimSetup* setup, const DisturbanceOverrides& overrides) {
  Rng rng(setup->seed ^ 0x5BAC7ull);
  ChassisVibrationSpec spec;
  spec.rest_rms_mps2 = rng.Uniform(0.5, 1.0);
  spec.drive_rms_mps2 = rng.Uniform(1.0, 2.0);
  spec.rest_rms_mps2 = overrides.vibration_rest_rms_mps2.value_or(spec.rest_rms_mps2);
  spec.drive_rms_mps2 = overrides.vibration_drive_rms_mps2.value_or(spec.drive_rms_mps2);
  setup->trajectory->SetVibration(
      std::make_shared<ChassisVibration>(spec, overrides.vibration_seed.value_or(setup->seed)));
}

void SetUp(SimSetup* setup, Disturbance d, const DisturbanceOverrides& overrides) {
  switch (d) {
    case Disturbance::kTimeOffset:
      SetUpTimeOffset(setup, overrides);
      break;
    case Disturbance::kVibration:
      SetUpVibration(setup, overrides);
      break;
    case Disturbance::kPeople:
      SetUpPeople(setup);
      break;
    case Disturbance::kVehicles:
      SetUpVehicles(setup);
      break;
    case Disturbance::kMixedPixels:
      SetUpMixedPixels(setup);
      break;
    case Disturbance::kRain:
      SetUpRain(setup);
      break;
    case Disturbance::kDust:
      SetUpDust(setup);
      break;
    case Disturbance::kDropouts:
      SetUpDropouts(setup);
      break;
    case Disturbance::kTemperature:
      SetUpTemperature(setup);
      break;
  }
}

}  // namespace

void ApplyDisturbances(SimSetup* setup,
                       const DisturbanceSet& set,
                       const DisturbanceOverrides& overrides) {
  for (Disturbance d : AllDisturbances()) {
    if (!set.Has(d)) continue;
    // An override applies even to a disturbance already on (the scenario's own).
    const bool overridden = (d == Disturbance::kTimeOffset && overrides.time_offset_s) ||
                            (d == Disturbance::kVibration &&
                             (overrides.vibration_rest_rms_mps2 ||
                              overrides.vibration_drive_rms_mps2 || overrides.vibration_seed));
    if (setup->disturb.Has(d) && !overridden) continue;
    SetUp(setup, d, overrides);
  }
  setup->disturb.Add(set);
}

}  // namespace swlio::sim

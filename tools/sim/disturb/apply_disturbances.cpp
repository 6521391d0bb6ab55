#include "disturb/apply_disturbances.h"

#include "disturb/actor_setup.h"
#include "rng.h"

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

void SetUp(SimSetup* setup, Disturbance d, const DisturbanceOverrides& overrides) {
  switch (d) {
    case Disturbance::kTimeOffset:
      SetUpTimeOffset(setup, overrides);
      break;
    case Disturbance::kPeople:
      SetUpPeople(setup);
      break;
    case Disturbance::kVehicles:
      SetUpVehicles(setup);
      break;
    // The other models are set up by their own files as they land (issue 36).
    case Disturbance::kVibration:
    case Disturbance::kMixedPixels:
    case Disturbance::kRain:
    case Disturbance::kDust:
    case Disturbance::kDropouts:
    case Disturbance::kTemperature:
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
    if (setup->disturb.Has(d) && !(d == Disturbance::kTimeOffset && overrides.time_offset_s)) {
      continue;
    }
    SetUp(setup, d, overrides);
  }
  setup->disturb.Add(set);
}

}  // namespace swlio::sim

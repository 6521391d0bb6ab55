#include "disturb/disturbance_manifest.h"

#include <sstream>

#include "disturb/weather_setup.h"
#include "swlio/core/exact_number.h"

namespace swlio::sim {

std::string DisturbanceManifestBlock(const SimSetup& setup) {
  std::ostringstream y;
  y << "disturbances:  # field disturbances (swlio-sim --disturb), issue 36\n"
    << "  list: " << setup.disturb.ToString() << "\n";
  if (setup.disturb.Has(Disturbance::kTimeOffset)) {
    y << "  # each IMU sample measures the motion of time_offset_s before the host time its\n"
      << "  # SampleTimeFine maps to: the estimator should find it as the IMU-LiDAR offset\n"
      << "  time_offset_s: " << ExactNumber(setup.imu.time_offset_s) << "\n";
  }
  y << WeatherManifestLines(setup);
  return y.str();
}

}  // namespace swlio::sim

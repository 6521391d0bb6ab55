#pragma once
// Test support: the simulated RS-LiDAR-16's ray-cast truth over a span of one drive, for tests
// that compare a drive with and without a disturbance (sim_lidar_noise_test, sim_weather_test).

#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/lidar_sim.h"

namespace swlio::test {

struct LidarCast {
  std::vector<sim::SimReturn> truth;  ///< every MSOP slot's
  sim::WeatherCounts counts;          ///< the weather's counts (zero without weather)
};

/// Every MSOP slot's truth from `from_s` to `to_s` (sim time), the sweep cast from `from_s` on
/// (SkipTo), with `config` as the LiDAR's.
inline LidarCast Cast(const sim::SimSetup& setup,
                      const sim::LidarSimConfig& config,
                      double from_s,
                      double to_s) {
  sim::LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), config, setup.seed);
  lidar.SkipTo(from_s);
  LidarCast run;
  std::vector<sim::SimReturn> packet_truth;
  sim::SimPacket packet;
  while (lidar.Next(&packet, &packet_truth) && packet.t_header_s < to_s) {
    run.truth.insert(run.truth.end(), packet_truth.begin(), packet_truth.end());
  }
  if (lidar.weather() != nullptr) run.counts = lidar.weather()->counts();
  return run;
}

}  // namespace swlio::test

#pragma once
/// @file
/// Everything a simulated run is made of, derived from (scenario name, seed): the world, the
/// route, the sensor models with their clocks and the true IMU-LiDAR extrinsic. Shared by the
/// file writer, the live sender and tests.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "disturb/disturbances.h"
#include "scenarios/scenarios.h"
#include "scenarios/trajectory.h"
#include "sensors/gnss_sim.h"
#include "sensors/imu_sim.h"
#include "sensors/lidar_sim.h"
#include "sensors/wheel_sim.h"
#include "world/world.h"

namespace swlio::sim {

struct SimSetup {
  Scenario scenario;
  uint64_t seed = 0;             ///< noise, clocks, extrinsic (and revisit's start)
  uint64_t world_seed = 0;       ///< the substation (the seed unless given apart)
  std::unique_ptr<World> world;  ///< heap: the trajectory points into its terrain
  std::unique_ptr<Trajectory> trajectory;
  ImuSimConfig imu;
  LidarSimConfig lidar;       ///< includes T_imu_lidar and the LiDAR clock
  GnssSimConfig gnss;         ///< the MTi's GNSS items (their rate: imu.gnss_pvt_period_s)
  WheelSimConfig wheel;       ///< chassis odometry on CAN (T_imu_base, drawn scale errors)
  double gt_rate_hz = 200.0;  ///< ground-truth pose rate
  /// The field disturbances that are on (disturb/apply_disturbances.h); their models live in
  /// the configurations above.
  DisturbanceSet disturb;
};

/// Builds the setup; `duration_s` (when given) shortens the route's timeline; `world_seed`
/// (when given) draws the substation from another seed than the drive (a second drive in a
/// world mapped before); `stand_start_s` (when given) replaces the scenario's standing time
/// before the robot drives off (an inspection stop at the start). Returns nothing for an
/// unknown scenario.
std::optional<SimSetup> MakeSimSetup(const std::string& scenario,
                                     uint64_t seed,
                                     std::optional<double> duration_s = std::nullopt,
                                     std::optional<uint64_t> world_seed = std::nullopt,
                                     std::optional<double> stand_start_s = std::nullopt);

/// Trajectory duration after the optional cut.
double SimDuration(const SimSetup& setup);

/// Sets the IMU clock's offset so that the Xsens SampleTimeFine counter (100 µs ticks, 2³² of
/// them) wraps at simulation time `at_s` (a fault to inject).
void SetImuWrapAt(SimSetup* setup, double at_s);

}  // namespace swlio::sim

#include "scenarios/sim_setup.h"

#include <algorithm>

#include "disturb/apply_disturbances.h"
#include "rng.h"
#include "swlio/core/lie.h"
#include "world/substation.h"

namespace swlio::sim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// The LiDAR sits below the IMU (as in the paper's robot), its x axis (azimuth 0 in the
/// drivers' frame) forward like the IMU's: a little mounting error about zero, and a lever arm
/// of about 12 cm.
Eigen::Isometry3d TrueExtrinsic(Rng& rng) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      lie::QuatFromRpy(rng.Normal(0.8) * kDeg, rng.Normal(0.8) * kDeg, rng.Normal(1.0) * kDeg)
          .toRotationMatrix();
  T.translation() =
      Eigen::Vector3d(0.03 + rng.Normal(0.01), -0.01 + rng.Normal(0.01), -0.12 + rng.Normal(0.01));
  return T;
}

/// The chassis base right below the IMU on the ground, axes as the IMU's (x forward, z up).
/// Not ahead of or behind it: the route moves the IMU along its heading, so the point below it
/// is the one without sideways speed, i.e. the differential drive's axle midpoint; a base
/// elsewhere would slide sideways in turns against the non-holonomic model.
/// Wheel radius errors: one draw per seed.
void SetUpWheels(const RouteSpec& route, uint64_t seed, WheelSimConfig* wheel) {
  wheel->T_imu_base = Eigen::Isometry3d::Identity();
  wheel->T_imu_base.translation() = Eigen::Vector3d(0.0, 0.0, -route.imu_height_m);
  Rng rng(seed ^ 0x3EE1ull);
  wheel->noise.scale_error_left = rng.Normal(wheel->noise.scale_error_sigma);
  wheel->noise.scale_error_right = rng.Normal(wheel->noise.scale_error_sigma);
}

}  // namespace

std::optional<SimSetup> MakeSimSetup(const std::string& scenario,
                                     uint64_t seed,
                                     std::optional<double> duration_s,
                                     std::optional<uint64_t> world_seed,
                                     std::optional<double> stand_start_s) {
  std::optional<Scenario> s = MakeScenario(scenario, seed);
  if (!s) return std::nullopt;
  SimSetup setup;
  setup.scenario = *s;
  setup.seed = seed;
  setup.world_seed = world_seed.value_or(seed);
  setup.world = std::make_unique<World>(GenerateSubstation(setup.world_seed));
  for (const Bump& b : s->extra_bumps) setup.world->terrain.bumps.push_back(b);
  if (stand_start_s) s->route.stand_start_s = *stand_start_s;
  setup.trajectory = std::make_unique<Trajectory>(s->route, &setup.world->terrain);
  Rng rng(seed ^ 0xC10C4ull);
  // LiDAR header clock: UTC-like (2023-11 plus up to a day), drifting up to ±20 ppm.
  setup.lidar.clock.offset_s = 1'700'000'000.0 + rng.Uniform(0.0, 86'400.0);
  setup.lidar.clock.drift_ppm = rng.Uniform(-20.0, 20.0);
  setup.lidar.initial_azimuth_deg = rng.Uniform(0.0, 360.0);
  setup.lidar.T_imu_lidar = TrueExtrinsic(rng);
  // IMU SampleTimeFine: device uptime (up to ~11 h) drifting up to ±50 ppm.
  setup.imu.clock.offset_s = rng.Uniform(10.0, 40'000.0);
  setup.imu.clock.drift_ppm = rng.Uniform(-50.0, 50.0);
  SetUpWheels(s->route, seed, &setup.wheel);
  if (duration_s) {
    setup.trajectory->Truncate(std::max(0.1, *duration_s));
  }
  ApplyDisturbances(&setup, setup.scenario.disturb);
  return setup;
}

double SimDuration(const SimSetup& setup) { return setup.trajectory->duration_s(); }

void SetImuWrapAt(SimSetup* setup, double at_s) {
  constexpr double kWrapS = 4294967296.0 * 1e-4;  // 2³² ticks of 100 µs
  auto& c = setup->imu.clock;
  c.offset_s = kWrapS - at_s * (1.0 + c.drift_ppm * 1e-6);
}

}  // namespace swlio::sim

#include "sim_setup.h"

#include <algorithm>

#include "rng.h"
#include "substation.h"
#include "swlio/core/lie.h"

namespace swlio::sim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// The LiDAR sits below the IMU (as in the paper's robot), its manual frame's y axis forward:
/// a −90° yaw plus a little mounting error, and a lever arm of about 12 cm.
Eigen::Isometry3d TrueExtrinsic(Rng& rng) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::QuatFromRpy(rng.Normal(0.8) * kDeg, rng.Normal(0.8) * kDeg,
                                (-90.0 + rng.Normal(1.0)) * kDeg)
                   .toRotationMatrix();
  T.translation() =
      Eigen::Vector3d(0.03 + rng.Normal(0.01), -0.01 + rng.Normal(0.01), -0.12 + rng.Normal(0.01));
  return T;
}

}  // namespace

std::optional<SimSetup> MakeSimSetup(const std::string& scenario,
                                     uint64_t seed,
                                     std::optional<double> duration_s,
                                     std::optional<uint64_t> world_seed) {
  std::optional<Scenario> s = MakeScenario(scenario, seed);
  if (!s) return std::nullopt;
  SimSetup setup;
  setup.scenario = *s;
  setup.seed = seed;
  setup.world_seed = world_seed.value_or(seed);
  setup.world = std::make_unique<World>(GenerateSubstation(setup.world_seed));
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
  if (duration_s) {
    setup.trajectory->Truncate(std::max(0.1, *duration_s));
  }
  return setup;
}

double SimDuration(const SimSetup& setup) { return setup.trajectory->duration_s(); }

void SetImuWrapAt(SimSetup* setup, double at_s) {
  constexpr double kWrapS = 4294967296.0 * 1e-4;  // 2³² ticks of 100 µs
  auto& c = setup->imu.clock;
  c.offset_s = kWrapS - at_s * (1.0 + c.drift_ppm * 1e-6);
}

}  // namespace swlio::sim

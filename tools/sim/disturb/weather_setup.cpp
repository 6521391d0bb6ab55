#include "disturb/weather_setup.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include "rng.h"
#include "swlio/core/exact_number.h"
#include "swlio/core/time.h"

namespace swlio::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kG = 9.80665;

/// Temperature coefficients of the offset of an uncompensated MEMS IMU: gyro ±0.015 °/s/K,
/// accelerometer ±0.2 mg/K (Bosch BMI088 data sheet BST-BMI088-DS001, specification tables,
/// "TCO"). The MTi-G-710 models each unit's bias over temperature in its firmware (MTi user
/// manual MT0605P, §5.8.1), so only a residual is left: assumed 10 % of those figures.
constexpr double kGyroTcoRadpsPerC = 0.015 * kDegToRad;
constexpr double kAccTcoMps2PerC = 0.2e-3 * kG;
constexpr double kResidualAfterCompensation = 0.1;

/// Dust: a puff every 8 s on average while the robot drives faster than 0.3 m/s, lasting
/// 1.5–4 s, 0.5–1.5 m behind the IMU and up to 0.6 m to its side, 0.2–0.6 m above the ground,
/// 0.3–0.8 m in radius, blown at 0.5–2 m/s, 0.1–0.6 scattering events per metre (assumed; the
/// clouds of Phillips et al., ACRA 2017, near the vehicle, intermittent, low).
constexpr double kDustMeanIntervalS = 8.0;
constexpr double kDustMinSpeedMps = 0.3;

DustPuff DrawPuff(const SimSetup& setup, double t_s, Rng& rng) {
  const Kinematics k = setup.trajectory->At(t_s);
  DustPuff p;
  p.t_start_ns = SecToNs(t_s);
  p.t_end_ns = SecToNs(t_s + rng.Uniform(1.5, 4.0));
  const double height = rng.Uniform(0.2, 0.6) - setup.scenario.route.imu_height_m;
  const Eigen::Vector3d offset_body(-rng.Uniform(0.5, 1.5), rng.Uniform(-0.6, 0.6), height);
  p.center_world = k.p_world + k.R_world_body * offset_body;
  const double wind_dir = rng.Uniform(0.0, 2.0 * std::numbers::pi);
  p.wind_world_mps =
      rng.Uniform(0.5, 2.0) * Eigen::Vector3d(std::cos(wind_dir), std::sin(wind_dir), 0.0);
  p.radius_m = rng.Uniform(0.3, 0.8);
  p.extinction_per_m = rng.Uniform(0.1, 0.6);
  return p;
}

}  // namespace

void SetUpMixedPixels(SimSetup* setup) { setup->lidar.weather.mixed.on = true; }

void SetUpRain(SimSetup* setup) {
  setup->lidar.weather.rain.on = true;
  setup->lidar.weather.rain.near_min_m = setup->lidar.min_range_m;
}

void SetUpDust(SimSetup* setup) {
  DustConfig& dust = setup->lidar.weather.dust;
  dust.on = true;
  dust.puffs.clear();
  Rng rng(setup->seed ^ 0xD057ull);
  const double duration_s = setup->trajectory->duration_s();
  for (double t = -kDustMeanIntervalS * std::log(1.0 - rng.Uniform()); t < duration_s;
       t += -kDustMeanIntervalS * std::log(1.0 - rng.Uniform())) {
    if (setup->trajectory->At(t).v_world.norm() < kDustMinSpeedMps) continue;
    dust.puffs.push_back(DrawPuff(*setup, t, rng));
  }
}

void SetUpDropouts(SimSetup* setup) {
  DetectionConfig& d = setup->lidar.weather.detection;
  d.on = true;
  d.puddle_seed = setup->seed ^ 0x9DDull;
}

void SetUpTemperature(SimSetup* setup) {
  ImuTemperatureConfig& t = setup->imu.temperature;
  t.on = true;
  Rng rng(setup->seed ^ 0x7E3Dull);
  for (int i = 0; i < 3; ++i) {
    t.gyro_bias_per_c(i) = kResidualAfterCompensation * kGyroTcoRadpsPerC * rng.Uniform(-1.0, 1.0);
    t.acc_bias_per_c(i) = kResidualAfterCompensation * kAccTcoMps2PerC * rng.Uniform(-1.0, 1.0);
  }
}

std::string WeatherManifestLines(const SimSetup& setup) {
  std::ostringstream y;
  const LidarWeatherConfig& w = setup.lidar.weather;
  // A stream, not string +: GCC 12 warns falsely (-Wrestrict) on that concatenation.
  auto vec = [](const Eigen::Vector3d& v) {
    std::ostringstream out;
    out << "[" << ExactNumber(v.x()) << ", " << ExactNumber(v.y()) << ", " << ExactNumber(v.z())
        << "]";
    return out.str();
  };
  if (w.mixed.on) {
    y << "  # mixed pixels: power-weighted mean range where the footprint straddles an edge\n"
      << "  mixed_pixel_divergence_rad: " << ExactNumber(w.mixed.divergence_rad) << "\n";
  }
  if (w.rain.on) {
    y << "  rain_rate_mm_per_h: " << ExactNumber(w.rain.rate_mm_per_h) << "\n"
      << "  rain_echoes_per_ray: " << ExactNumber(RainEchoesPerRay(w.rain)) << "\n"
      << "  rain_near_max_m: " << ExactNumber(w.rain.near_max_m) << "\n";
  }
  if (w.dust.on) {
    y << "  # dust puffs: t_start_s, t_end_s, centre_world_m at t_start, wind_mps, radius_m\n"
      << "  dust_puffs: " << w.dust.puffs.size() << "\n";
    for (size_t i = 0; i < w.dust.puffs.size(); ++i) {
      const DustPuff& p = w.dust.puffs[i];
      y << "  dust_puff_" << i << ": [" << ExactNumber(NsToSec(p.t_start_ns)) << ", "
        << ExactNumber(NsToSec(p.t_end_ns)) << ", " << vec(p.center_world) << ", "
        << vec(p.wind_world_mps) << ", " << ExactNumber(p.radius_m) << "]\n";
    }
  }
  if (w.detection.on) {
    y << "  dropout_reference: [" << ExactNumber(w.detection.reference_reflectivity) << ", "
      << ExactNumber(w.detection.reference_range_m) << "]  # reflectivity, range at p = 0.5\n"
      << "  wet_ground_factor: " << ExactNumber(w.detection.wet_ground_factor) << "\n"
      << "  puddle_fraction: " << ExactNumber(w.detection.puddle_fraction) << "\n";
  }
  const ImuTemperatureConfig& t = setup.imu.temperature;
  if (t.on) {
    y << "  # IMU temperature T(t) = start + rise*(1 - exp(-t/tau)); bias += coeff*(T - start)\n"
      << "  imu_temperature_start_c: " << ExactNumber(t.start_c) << "\n"
      << "  imu_temperature_rise_c: " << ExactNumber(t.rise_c) << "\n"
      << "  imu_temperature_tau_s: " << ExactNumber(t.time_constant_s) << "\n"
      << "  imu_gyro_bias_per_c_radps: " << vec(t.gyro_bias_per_c) << "\n"
      << "  imu_acc_bias_per_c_mps2: " << vec(t.acc_bias_per_c) << "\n";
  }
  return y.str();
}

}  // namespace swlio::sim

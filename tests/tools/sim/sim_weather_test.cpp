// Weather, edges and dark or wet surfaces in the simulated RS-LiDAR-16 (sensors/lidar_weather.h,
// disturb/weather_setup.h): each model changes what it should and nothing else, by the
// ray-cast truth of a run without it on the same seed.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <vector>

#include "disturb/apply_disturbances.h"
#include "disturb/disturbance_manifest.h"
#include "disturb/weather_setup.h"
#include "lidar_cast.h"
#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/time.h"

namespace swlio::sim {
namespace {

SimSetup SetupOrDie(const std::string& name, uint64_t seed, double duration_s) {
  auto s = MakeSimSetup(name, seed, duration_s);
  EXPECT_TRUE(s.has_value());
  return std::move(*s);
}

using test::Cast;

bool SameSlot(const SimReturn& a, const SimReturn& b) {
  return a.t_true_ns == b.t_true_ns && a.channel == b.channel;
}

TEST(SimWeather, RainAddsReturnsOnlyWithinItsNearRange) {
  SimSetup setup = SetupOrDie("aggressive", 2, 6.0);
  const std::vector<SimReturn> clean = Cast(setup, setup.lidar, 3.0, 4.0).truth;
  SetUpRain(&setup);
  const std::vector<SimReturn> rain = Cast(setup, setup.lidar, 3.0, 4.0).truth;
  ASSERT_EQ(clean.size(), rain.size());
  size_t drops = 0, lost = 0;
  for (size_t i = 0; i < clean.size(); ++i) {
    ASSERT_TRUE(SameSlot(clean[i], rain[i]));
    if (clean[i].true_range_m == rain[i].true_range_m) continue;
    if (rain[i].true_range_m < 0.0) {  // attenuated: only surfaces far enough to feel it
      EXPECT_GT(clean[i].true_range_m, 20.0);
      ++lost;
      continue;
    }
    ++drops;
    EXPECT_EQ(rain[i].cls, SurfaceClass::kNone);
    EXPECT_GE(rain[i].true_range_m, setup.lidar.min_range_m);
    EXPECT_LE(rain[i].true_range_m, setup.lidar.weather.rain.near_max_m);
    if (clean[i].true_range_m > 0.0) {
      EXPECT_LT(rain[i].true_range_m, clean[i].true_range_m);
    }
  }
  const double per_sweep = static_cast<double>(drops) / 10.0;  // 1 s at 600 rpm
  std::printf("rain 5 mm/h: %.1f drop returns per sweep, %.1f surface returns lost per sweep\n",
              per_sweep, static_cast<double>(lost) / 10.0);
  EXPECT_GT(per_sweep, 10.0);
  EXPECT_LT(per_sweep, 300.0);
  EXPECT_GT(lost, 0u) << "the rain's attenuation costs some far returns";
  EXPECT_LT(lost, drops) << "but few at 5 mm/h";
}

/// Rays from the LiDAR's pose at `t_s` over a full turn, every 0.2° for each laser.
std::vector<WeatherRay> TurnOfRays(const SimSetup& setup, double t_s) {
  const Kinematics k = setup.trajectory->At(t_s);
  Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
  T_world_imu.linear() = k.R_world_body;
  T_world_imu.translation() = k.p_world;
  const Eigen::Isometry3d T_world_lidar = T_world_imu * setup.lidar.T_imu_lidar;
  std::vector<WeatherRay> rays;
  for (int step = 0; step < 1800; ++step) {
    const double alpha = step * 0.2 * std::numbers::pi / 180.0;
    for (int laser = 0; laser < 16; ++laser) {
      WeatherRay r;
      r.t_ns = SecToNs(t_s);
      r.laser = laser;
      r.origin_world = T_world_lidar * SimLensCentre(setup.lidar, alpha);
      r.dir_world =
          T_world_lidar.linear() * SimRayDirection(setup.lidar, static_cast<size_t>(laser), alpha);
      r.up_world = T_world_lidar.linear().col(2);
      rays.push_back(r);
    }
  }
  return rays;
}

/// A changed return lies strictly between the centre's surface and a surface that a sub-ray
/// inside the footprint hits; where the footprint sees one surface nothing changes.
TEST(SimWeather, MixedPixelsLieBetweenTwoSurfacesAtEdgesOnly) {
  SimSetup setup = SetupOrDie("aggressive", 3, 12.0);
  LidarWeatherConfig config;
  config.mixed.on = true;
  config.mixed.every_ray = true;
  LidarWeather weather(setup.world.get(), config, 3);
  const double w = 0.5 * config.mixed.divergence_rad;
  size_t changed = 0, returns = 0;
  for (const WeatherRay& ray : TurnOfRays(setup, 8.0)) {
    const RayHit clean = setup.world->Cast(ray.origin_world, ray.dir_world, 150.0);
    RayHit hit = clean;
    weather.Apply(ray, 150.0, &hit);
    if (clean.range_m <= 0.0) continue;
    ++returns;
    double lo = clean.range_m, hi = clean.range_m;
    for (const double s : {-w, w}) {
      const Eigen::AngleAxisd turn(s, ray.up_world);
      const RayHit side = setup.world->Cast(ray.origin_world, turn * ray.dir_world, 150.0);
      if (side.range_m > 0.0) {
        lo = std::min(lo, side.range_m);
        hi = std::max(hi, side.range_m);
      }
    }
    if (hit.range_m == clean.range_m) continue;
    ++changed;
    EXPECT_GT(hi - lo, config.mixed.edge_jump_m) << "moved without an edge in the footprint";
    EXPECT_GT(hit.range_m, lo);
    EXPECT_LT(hit.range_m, hi);
  }
  std::printf("mixed pixels: %zu of %zu returns of a turn (%.2f %%)\n", changed, returns,
              100.0 * static_cast<double>(changed) / static_cast<double>(returns));
  EXPECT_GT(changed, 10u);
  EXPECT_LT(changed, returns / 10);
}

/// The cheap test (a range jump against the previous firing) against probing every footprint:
/// the fraction of a drive's returns each moves, and what each costs in casts.
TEST(SimWeather, MixedPixelsOnADrive) {
  SimSetup setup = SetupOrDie("aggressive", 1, 8.0);
  for (const bool every_ray : {false, true}) {
    LidarSimConfig config = setup.lidar;
    config.weather.mixed.on = true;
    config.weather.mixed.every_ray = every_ray;
    const test::LidarCast run = Cast(setup, config, 4.0, 5.0);
    size_t returns = 0;
    for (const SimReturn& r : run.truth) returns += r.true_range_m > 0.0 ? 1 : 0;
    const WeatherCounts& c = run.counts;
    std::printf(
        "mixed pixels (%s): %.2f %% of returns moved, footprints probed %.2f %% of firings, "
        "%.3f extra casts per firing\n",
        every_ray ? "every ray" : "after a jump",
        100.0 * static_cast<double>(c.mixed) / static_cast<double>(returns),
        100.0 * static_cast<double>(c.edge_checks) / static_cast<double>(c.rays),
        static_cast<double>(c.sub_rays) / static_cast<double>(c.rays));
    EXPECT_GE(c.sub_rays, 2 * c.edge_checks);
    EXPECT_GT(c.mixed, 0u);
    EXPECT_LT(c.mixed, returns / 10);
  }
}

TEST(SimWeather, DetectionFallsWithReflectivityRangeAndIncidence) {
  DetectionConfig d;
  auto p = [&d](double rho, double r, double cos_inc = 1.0) {
    return DetectionProbability(d, rho * cos_inc / (r * r));
  };
  EXPECT_NEAR(p(0.20, 150.0), 0.5, 1e-12) << "the datasheet's range at its reflectivity";
  EXPECT_LT(p(0.05, 60.0), p(0.20, 60.0));
  EXPECT_LT(p(0.20, 120.0), p(0.20, 60.0));
  EXPECT_LT(p(0.20, 40.0, 0.02), p(0.20, 40.0, 1.0));
  EXPECT_GT(p(0.60, 20.0), 0.999);
  RainConfig rain;
  EXPECT_LT(RainTransmission(rain, 100.0), RainTransmission(rain, 10.0));
  EXPECT_GT(RainTransmission(rain, 100.0), 0.8) << "5 mm/h costs little power over 100 m";
}

/// Dropouts take surface returns only: more on the ground in puddles than on dry ground at the
/// same distance, more on far (grazing) ground than near.
TEST(SimWeather, DropoutsRiseOnDarkWetAndFarSurfaces) {
  SimSetup setup = SetupOrDie("aggressive", 4, 8.0);
  const std::vector<SimReturn> clean = Cast(setup, setup.lidar, 4.0, 5.0).truth;
  SetUpDropouts(&setup);
  const std::vector<SimReturn> wet = Cast(setup, setup.lidar, 4.0, 5.0).truth;
  ASSERT_EQ(clean.size(), wet.size());
  const DetectionConfig& d = setup.lidar.weather.detection;
  struct Tally {
    double lost = 0, all = 0;
    double Rate() const { return all > 0 ? lost / all : 0.0; }
  } puddle_near, puddle_far, dry_near, dry_far, other;
  for (size_t i = 0; i < clean.size(); ++i) {
    ASSERT_TRUE(SameSlot(clean[i], wet[i]));
    if (clean[i].true_range_m <= 0.0) {
      EXPECT_EQ(wet[i].true_range_m, clean[i].true_range_m) << "nothing appears";
      continue;
    }
    const bool lost = wet[i].true_range_m < 0.0;
    if (!lost) {
      EXPECT_EQ(wet[i].true_range_m, clean[i].true_range_m) << "ranges stay";
    }
    Tally* t = &other;
    if (clean[i].cls == SurfaceClass::kGround) {
      const Eigen::Vector3d& p = clean[i].p_world;
      const bool near = clean[i].true_range_m < 8.0;
      if (IsPuddle(d, p.x(), p.y())) {
        t = near ? &puddle_near : &puddle_far;
      } else {
        t = near ? &dry_near : &dry_far;
      }
    }
    t->all += 1.0;
    t->lost += lost ? 1.0 : 0.0;
  }
  std::printf(
      "dropouts lost: ground < 8 m %.1f %% (puddles %.1f %%), beyond %.1f %% (puddles %.1f %%), "
      "other surfaces %.1f %%\n",
      100 * dry_near.Rate(), 100 * puddle_near.Rate(), 100 * dry_far.Rate(),
      100 * puddle_far.Rate(), 100 * other.Rate());
  EXPECT_GT(puddle_near.all, 100.0);
  EXPECT_GT(puddle_far.all, 100.0);
  EXPECT_GT(puddle_near.Rate(), dry_near.Rate() + 0.2);
  EXPECT_GT(puddle_far.Rate(), dry_far.Rate());
  EXPECT_GT(dry_far.Rate(), dry_near.Rate());
  EXPECT_LT(other.Rate(), dry_far.Rate());
}

/// Dust returns lie inside a puff that is active at their firing time.
TEST(SimWeather, DustReturnsComeFromActivePuffsOnly) {
  SimSetup setup = SetupOrDie("aggressive", 1, 12.0);
  SimSetup clean_setup = SetupOrDie("aggressive", 1, 12.0);
  SetUpDust(&setup);
  const std::vector<DustPuff>& puffs = setup.lidar.weather.dust.puffs;
  ASSERT_FALSE(puffs.empty());
  const double from_s = NsToSec(puffs.front().t_start_ns) - 0.3;  // before it, and in it
  const std::vector<SimReturn> clean =
      Cast(clean_setup, clean_setup.lidar, from_s, from_s + 1.3).truth;
  const std::vector<SimReturn> dusty = Cast(setup, setup.lidar, from_s, from_s + 1.3).truth;
  ASSERT_EQ(clean.size(), dusty.size());
  size_t dust = 0, unchanged_outside = 0;
  for (size_t i = 0; i < clean.size(); ++i) {
    bool active = false, inside = false;
    for (const DustPuff& p : puffs) {
      if (dusty[i].t_true_ns < p.t_start_ns || dusty[i].t_true_ns > p.t_end_ns) continue;
      active = true;
      const double dt_s = NsToSec(dusty[i].t_true_ns - p.t_start_ns);
      const Eigen::Vector3d c = p.center_world + dt_s * p.wind_world_mps;
      inside = inside || (dusty[i].p_world - c).norm() <= p.radius_m + 1e-6;
    }
    if (!active) {
      EXPECT_EQ(clean[i].true_range_m, dusty[i].true_range_m) << "no puff, no change";
      ++unchanged_outside;
      continue;
    }
    if (clean[i].true_range_m == dusty[i].true_range_m) continue;
    if (dusty[i].true_range_m < 0.0) continue;  // lost in the cloud
    ++dust;
    EXPECT_TRUE(inside);
    EXPECT_EQ(dusty[i].cls, SurfaceClass::kNone);
  }
  std::printf("dust: %zu returns in the first puff's first second (%zu puffs in 12 s)\n", dust,
              puffs.size());
  EXPECT_GT(dust, 50u);
  EXPECT_GT(unchanged_outside, 0u) << "the second also holds firings without a puff";
}

TEST(SimWeather, DeterministicPerSeedAndOnlyTheLidarChanges) {
  auto all = ParseDisturbanceList("mixed_pixels,rain,dust,dropouts", nullptr);
  ASSERT_TRUE(all);
  auto bytes = [](const SimSetup& s) {
    LidarSimulator lidar(s.world.get(), s.trajectory.get(), s.lidar, s.seed);
    lidar.SkipTo(3.0);
    std::vector<uint8_t> out;
    SimPacket packet;
    while (lidar.Next(&packet) && packet.t_header_s < 3.3) {
      out.insert(out.end(), packet.bytes.begin(), packet.bytes.end());
    }
    return out;
  };
  SimSetup a = SetupOrDie("aggressive", 5, 6.0), b = SetupOrDie("aggressive", 5, 6.0);
  SimSetup c = SetupOrDie("aggressive", 6, 6.0), clean = SetupOrDie("aggressive", 5, 6.0);
  for (SimSetup* s : {&a, &b, &c}) ApplyDisturbances(s, *all);
  EXPECT_EQ(bytes(a), bytes(b));
  EXPECT_NE(bytes(a), bytes(clean));
  EXPECT_EQ(DisturbanceManifestBlock(a), DisturbanceManifestBlock(b));
  EXPECT_NE(DisturbanceManifestBlock(a), DisturbanceManifestBlock(c));
  const std::vector<SimImuSample> imu_a = SimulateImu(*a.trajectory, a.imu, 5);
  const std::vector<SimImuSample> imu_clean = SimulateImu(*clean.trajectory, clean.imu, 5);
  ASSERT_EQ(imu_a.size(), imu_clean.size());
  for (size_t i = 0; i < imu_a.size(); i += 97) {
    EXPECT_EQ(imu_a[i].acc_mps2, imu_clean[i].acc_mps2);
    EXPECT_EQ(imu_a[i].gyro_radps, imu_clean[i].gyro_radps);
  }
}

/// Readers match manifest lines by key: each key the weather writes appears once in the file.
TEST(SimWeather, ManifestKeysAreUnique) {
  SimSetup setup = SetupOrDie("aggressive", 1, 30.0);
  ApplyDisturbances(&setup,
                    *ParseDisturbanceList("mixed_pixels,rain,dust,dropouts,temperature", nullptr));
  const std::string manifest = ManifestYaml(setup, RecordingStats{}, 0, "file");
  std::istringstream lines(WeatherManifestLines(setup));
  std::string line;
  size_t keys = 0;
  while (std::getline(lines, line)) {
    const size_t colon = line.find(':');
    if (line.find('#') != std::string::npos && line.find('#') < colon) continue;
    const std::string key = "\n" + line.substr(0, colon + 1);
    size_t count = 0;
    for (size_t at = manifest.find(key); at != std::string::npos; at = manifest.find(key, at + 1)) {
      ++count;
    }
    EXPECT_EQ(count, 1u) << key;
    ++keys;
  }
  EXPECT_GE(keys, 15u);
}

}  // namespace
}  // namespace swlio::sim

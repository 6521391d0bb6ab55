// The simulated LiDAR's noise is tied to each ray (KeyedDraws in rng.h, sensors/lidar_sim.cpp):
// a drive with a disturbance and the same drive without it differ by the disturbance alone, and
// a sweep cast on its own (SkipTo) is the full run's sweep.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "disturb/weather_setup.h"
#include "lidar_cast.h"
#include "rng.h"
#include "scenarios/sim_setup.h"

namespace swlio::sim {
namespace {

/// Every MSOP slot's truth over sim time [from_s, to_s) with the setup's own LiDAR.
std::vector<SimReturn> Cast(const SimSetup& setup, double from_s, double to_s) {
  return test::Cast(setup, setup.lidar, from_s, to_s).truth;
}

TEST(KeyedDraws, AKeyGetsTheSameNumbersWhateverElseWasDrawn) {
  KeyedDraws a(7, 42);
  KeyedDraws other(7, 41);
  for (int i = 0; i < 100; ++i) other.Uniform();
  KeyedDraws b(7, 42);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(a.Uniform(), b.Uniform());
  EXPECT_NE(KeyedDraws(7, 42).Uniform(), KeyedDraws(8, 42).Uniform()) << "the seed matters";
  EXPECT_NE(KeyedDraws(7, 42).Uniform(), KeyedDraws(7, 43).Uniform()) << "the key matters";
}

TEST(KeyedDraws, NormalHasTheGivenSpreadAndNoMean) {
  double sum = 0.0, sum2 = 0.0;
  constexpr int kN = 200000;
  for (uint64_t key = 0; key < kN; ++key) {
    const double x = KeyedDraws(3, key).Normal(2.0);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / kN;
  EXPECT_NEAR(mean, 0.0, 0.02);  // 5 standard errors of 2/sqrt(kN)
  EXPECT_NEAR(std::sqrt(sum2 / kN - mean * mean), 2.0, 0.02);
}

TEST(SimLidarNoise, ASweepCastAloneIsTheFullRunsSweep) {
  auto setup = MakeSimSetup("aggressive", 2, 4.0);
  ASSERT_TRUE(setup.has_value());
  const std::vector<SimReturn> full = Cast(*setup, 2.0, 3.2);
  const std::vector<SimReturn> alone = Cast(*setup, 3.0, 3.2);
  ASSERT_FALSE(alone.empty());
  // The same slots at the same times, so the tail of `full` lines up with `alone`.
  ASSERT_GE(full.size(), alone.size());
  const size_t offset = full.size() - alone.size();
  size_t returns = 0;
  for (size_t i = 0; i < alone.size(); ++i) {
    const SimReturn& f = full[offset + i];
    ASSERT_EQ(f.t_true_ns, alone[i].t_true_ns) << i;
    ASSERT_EQ(f.range_m, alone[i].range_m) << "slot " << i << " at " << f.t_true_ns;
    if (f.range_m > 0.0) ++returns;
  }
  EXPECT_GT(returns, alone.size() / 2) << "a sweep with returns was compared";
}

TEST(SimLidarNoise, RaysADisturbanceLeavesKeepTheirNoise) {
  // Rain changes a few rays (echoes near the sensor, attenuation far off); every other ray has
  // the noise it has without rain. Drawn from one stream, every ray after the first changed one
  // would have had other noise.
  auto clean_setup = MakeSimSetup("aggressive", 2, 5.0);
  auto rain_setup = MakeSimSetup("aggressive", 2, 5.0);
  ASSERT_TRUE(clean_setup.has_value() && rain_setup.has_value());
  SetUpRain(&*rain_setup);
  const std::vector<SimReturn> clean = Cast(*clean_setup, 3.0, 4.0);
  const std::vector<SimReturn> rain = Cast(*rain_setup, 3.0, 4.0);
  ASSERT_EQ(clean.size(), rain.size());
  size_t untouched = 0, same_noise = 0, touched = 0;
  for (size_t i = 0; i < clean.size(); ++i) {
    ASSERT_EQ(clean[i].t_true_ns, rain[i].t_true_ns);
    if (clean[i].true_range_m != rain[i].true_range_m) {
      ++touched;
      continue;
    }
    if (clean[i].range_m <= 0.0) continue;
    ++untouched;
    if (clean[i].range_m == rain[i].range_m) ++same_noise;
  }
  EXPECT_GT(touched, 0u) << "the rain changed some rays";
  EXPECT_GT(untouched, 10000u);
  EXPECT_EQ(same_noise, untouched);
}

}  // namespace
}  // namespace swlio::sim

// IMU bias drift with temperature (sensors/imu_temperature.h): the bias follows the warm-up
// profile times the drawn coefficients, on top of the random walk; nothing else changes.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "disturb/disturbance_manifest.h"
#include "disturb/weather_setup.h"
#include "scenarios/sim_setup.h"
#include "sensors/imu_temperature.h"
#include "swlio/core/exact_number.h"
#include "swlio/core/time.h"

namespace swlio::sim {
namespace {

TEST(SimImuTemperature, WarmUpProfile) {
  ImuTemperatureConfig t;
  t.start_c = 5.0;
  t.rise_c = 15.0;
  t.time_constant_s = 300.0;
  EXPECT_DOUBLE_EQ(ImuTemperatureC(t, 0.0), 5.0);
  EXPECT_NEAR(ImuTemperatureC(t, 300.0), 5.0 + 15.0 * (1.0 - std::exp(-1.0)), 1e-12);
  EXPECT_NEAR(ImuTemperatureC(t, 1e5), 20.0, 1e-9);
  EXPECT_EQ(ImuTemperatureGyroBias(t, 100.0), Eigen::Vector3d::Zero()) << "off: no bias";
}

/// Same seed with and without: the samples differ by exactly coeff·(T(t) − T0), per axis.
TEST(SimImuTemperature, BiasFollowsProfileTimesCoefficients) {
  auto setup = MakeSimSetup("aggressive", 7, 40.0);
  ASSERT_TRUE(setup);
  const std::vector<SimImuSample> clean = SimulateImu(*setup->trajectory, setup->imu, 7);
  SetUpTemperature(&*setup);
  const ImuTemperatureConfig& t = setup->imu.temperature;
  EXPECT_GT(t.gyro_bias_per_c.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE(t.gyro_bias_per_c.cwiseAbs().maxCoeff(), 0.1 * 0.015 * std::numbers::pi / 180.0);
  EXPECT_LE(t.acc_bias_per_c.cwiseAbs().maxCoeff(), 0.1 * 0.2e-3 * 9.80665);
  const std::vector<SimImuSample> warm = SimulateImu(*setup->trajectory, setup->imu, 7);
  ASSERT_EQ(clean.size(), warm.size());
  for (size_t i = 0; i < warm.size(); i += 37) {
    const double dT = ImuTemperatureC(t, NsToSec(warm[i].t_true_ns)) - t.start_c;
    EXPECT_NEAR((warm[i].bias_gyro - clean[i].bias_gyro - dT * t.gyro_bias_per_c).norm(), 0.0,
                1e-15);
    EXPECT_NEAR((warm[i].gyro_radps - clean[i].gyro_radps - dT * t.gyro_bias_per_c).norm(), 0.0,
                1e-12);
    EXPECT_NEAR((warm[i].acc_mps2 - clean[i].acc_mps2 - dT * t.acc_bias_per_c).norm(), 0.0, 1e-12);
    EXPECT_EQ(warm[i].t_rx_ns, clean[i].t_rx_ns);
  }
  const double dT_end = ImuTemperatureC(t, 40.0) - t.start_c;
  EXPECT_NEAR(dT_end, 15.0 * (1.0 - std::exp(-40.0 / 300.0)), 1e-9);
  const std::string manifest = DisturbanceManifestBlock(*setup);
  EXPECT_NE(manifest.find("imu_gyro_bias_per_c_radps: [" + ExactNumber(t.gyro_bias_per_c.x())),
            std::string::npos)
      << manifest;
  EXPECT_NE(manifest.find("imu_temperature_tau_s: 300"), std::string::npos) << manifest;
}

TEST(SimImuTemperature, LeavesTheLidarAlone) {
  auto clean = MakeSimSetup("aggressive", 8, 4.0), warm = MakeSimSetup("aggressive", 8, 4.0);
  ASSERT_TRUE(clean && warm);
  SetUpTemperature(&*warm);
  EXPECT_FALSE(warm->lidar.weather.Any());
  auto bytes = [](const SimSetup& s) {
    LidarSimulator lidar(s.world.get(), s.trajectory.get(), s.lidar, s.seed);
    std::vector<uint8_t> out;
    SimPacket packet;
    while (lidar.Next(&packet) && packet.t_header_s < 0.2) {
      out.insert(out.end(), packet.bytes.begin(), packet.bytes.end());
    }
    return out;
  };
  EXPECT_EQ(bytes(*clean), bytes(*warm));
}

TEST(SimImuTemperature, CoefficientsAreDrawnPerSeed) {
  auto a = MakeSimSetup("short", 1), b = MakeSimSetup("short", 1), c = MakeSimSetup("short", 2);
  ASSERT_TRUE(a && b && c);
  SetUpTemperature(&*a);
  SetUpTemperature(&*b);
  SetUpTemperature(&*c);
  EXPECT_EQ(a->imu.temperature.gyro_bias_per_c, b->imu.temperature.gyro_bias_per_c);
  EXPECT_NE(a->imu.temperature.gyro_bias_per_c, c->imu.temperature.gyro_bias_per_c);
}

}  // namespace
}  // namespace swlio::sim

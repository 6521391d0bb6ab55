// Field disturbances (disturb/disturbances.h, apply_disturbances.h): the list the command line
// takes, the `field` scenario, and the LiDAR–IMU time offset in the simulated IMU.

#include <gtest/gtest.h>

#include "disturb/apply_disturbances.h"
#include "disturb/disturbance_manifest.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/lie.h"

namespace swlio::sim {
namespace {

TEST(SimDisturbances, ListsParseAndPrint) {
  std::string error;
  auto set = ParseDisturbanceList("vibration,people", &error);
  ASSERT_TRUE(set) << error;
  EXPECT_TRUE(set->Has(Disturbance::kPeople));
  EXPECT_TRUE(set->Has(Disturbance::kVibration));
  EXPECT_FALSE(set->Has(Disturbance::kRain));
  EXPECT_EQ(set->ToString(), "people,vibration");
  auto all = ParseDisturbanceList("all", &error);
  ASSERT_TRUE(all);
  for (Disturbance d : AllDisturbances()) EXPECT_TRUE(all->Has(d)) << DisturbanceName(d);
  EXPECT_TRUE(ParseDisturbanceList("", &error)->Empty());
  EXPECT_EQ(ParseDisturbanceList("none", &error)->ToString(), "none");
  EXPECT_FALSE(ParseDisturbanceList("people,snow", &error));
  EXPECT_NE(error.find("'snow'"), std::string::npos) << error;
  EXPECT_FALSE(ParseDisturbanceList("people,,rain", &error)) << "an empty name is an error";
}

TEST(SimDisturbances, FieldIsLoop943WithEverything) {
  auto field = MakeSimSetup("field", 1);
  auto loop = MakeSimSetup("loop943", 1);
  ASSERT_TRUE(field && loop);
  for (Disturbance d : AllDisturbances()) EXPECT_TRUE(field->disturb.Has(d)) << DisturbanceName(d);
  EXPECT_TRUE(loop->disturb.Empty());
  EXPECT_DOUBLE_EQ(field->trajectory->length_m(), loop->trajectory->length_m());
  EXPECT_NE(DisturbanceManifestBlock(*field).find("time_offset_s: "), std::string::npos);
  EXPECT_NE(DisturbanceManifestBlock(*loop).find("list: none"), std::string::npos);
}

TEST(SimDisturbances, TimeOffsetIsDrawnPerSeedWithinTenMs) {
  double previous = 1.0;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    auto setup = MakeSimSetup("short", seed);
    ASSERT_TRUE(setup);
    EXPECT_EQ(setup->imu.time_offset_s, 0.0);
    ApplyDisturbances(&*setup, *ParseDisturbanceList("time_offset", nullptr));
    EXPECT_LE(std::abs(setup->imu.time_offset_s), 0.010);
    EXPECT_NE(setup->imu.time_offset_s, previous);
    previous = setup->imu.time_offset_s;
  }
  auto setup = MakeSimSetup("short", 1);
  DisturbanceOverrides fixed;
  fixed.time_offset_s = -0.007;
  ApplyDisturbances(&*setup, *ParseDisturbanceList("time_offset", nullptr), fixed);
  EXPECT_EQ(setup->imu.time_offset_s, -0.007);
}

/// Without noise, a sample stamped t measures the rate and specific force of t − offset.
TEST(SimDisturbances, TimeOffsetDelaysWhatTheImuMeasures) {
  auto setup = MakeSimSetup("aggressive", 3, 30.0);
  ASSERT_TRUE(setup);
  ImuSimConfig config = setup->imu;
  config.noise = ImuNoiseModel{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  config.gnss_pvt_period_s = 0.0;
  config.time_offset_s = 0.008;
  const std::vector<SimImuSample> delayed = SimulateImu(*setup->trajectory, config, 3);
  size_t checked = 0;
  for (size_t k = 1; k < delayed.size(); ++k) {
    const SimImuSample& s = delayed[k];
    const double t_s = static_cast<double>(s.t_true_ns) * 1e-9;
    const double dt_s = t_s - static_cast<double>(delayed[k - 1].t_true_ns) * 1e-9;
    if (t_s < 5.0) continue;
    // The sample is the mean rate over its interval (imu_sim.h), shifted by the offset.
    const Kinematics begin = setup->trajectory->At(t_s - dt_s - 0.008);
    const Kinematics then = setup->trajectory->At(t_s - 0.008);
    const Kinematics now = setup->trajectory->At(t_s);
    const Eigen::Vector3d mean_then =
        lie::Log(begin.R_world_body.transpose() * then.R_world_body) / dt_s;
    EXPECT_NEAR((s.gyro_radps - mean_then).norm(), 0.0, 1e-5);  // stamps rounded to 1 ns
    if ((now.omega_body - then.omega_body).norm() > 1e-3) ++checked;
  }
  EXPECT_GT(checked, 100u) << "the drive turns, so the offset is visible in the rate";
}

}  // namespace
}  // namespace swlio::sim

// The simulator's wheel odometry: the true base twist against a finite difference of the base's
// path, and the CAN frames (through the candump log and the daemon's WheelOdomDecoder) against
// that truth within the noise model.

#include "sensors/wheel_sim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "scenarios/sim_setup.h"
#include "swlio/core/time.h"
#include "swlio/drivers/candump_log.h"
#include "swlio/drivers/wheel_odom_decoder.h"

namespace swlio::sim {
namespace {

SimSetup MakeSetup(const std::string& name, uint64_t seed, double duration_s) {
  auto s = MakeSimSetup(name, seed, duration_s);
  EXPECT_TRUE(s.has_value());
  return std::move(*s);
}

/// The base origin's world position at t (rigidly attached to the IMU).
Eigen::Vector3d BaseInWorld(const Trajectory& trajectory,
                            const Eigen::Isometry3d& T_imu_base,
                            double t_s) {
  const Kinematics k = trajectory.At(t_s);
  return k.p_world + k.R_world_body * T_imu_base.translation();
}

TEST(SimWheel, BaseTwistIsTheDerivativeOfTheBasePath) {
  const SimSetup setup = MakeSetup("aggressive", 2, 30.0);
  const Eigen::Isometry3d& T = setup.wheel.T_imu_base;
  EXPECT_NEAR(T.translation().z(), -setup.scenario.route.imu_height_m, 1e-12) << "on the ground";
  constexpr double kH = 1e-4;
  double max_forward = 0.0;
  for (double t = 2.5; t < 29.0; t += 0.37) {
    const Eigen::Vector3d v_world =
        (BaseInWorld(*setup.trajectory, T, t + kH) - BaseInWorld(*setup.trajectory, T, t - kH)) /
        (2.0 * kH);
    const Kinematics k = setup.trajectory->At(t);
    const Eigen::Vector3d expected = T.linear().transpose() * k.R_world_body.transpose() * v_world;
    const BaseTwist twist = TrueBaseTwist(k, T);
    EXPECT_LT((twist.v_base_mps - expected).norm(), 1e-4) << "t = " << t;
    EXPECT_NEAR(twist.omega_base_radps.z(), k.omega_body.z(), 1e-12);  // identity rotation
    EXPECT_LT(std::abs(twist.v_base_mps.y()), 0.05) << "no sideways slide, t = " << t;
    max_forward = std::max(max_forward, twist.v_base_mps.x());
  }
  EXPECT_GT(max_forward, 1.0) << "the route moves";
}

struct Decoded {
  std::vector<drivers::WheelOdomSample> samples;
  drivers::CandumpCounters log;
};

/// The frames written as can.log and read back through the parser and the decoder.
Decoded ThroughCanLog(const WheelSimConfig& config, const std::vector<SimWheelSample>& sim) {
  std::stringstream log;
  EXPECT_TRUE(WriteCanLog(sim, 100 * kNsPerSec, log));
  auto decoder = drivers::WheelOdomDecoder::Create(WheelCanConfig(config));
  EXPECT_TRUE(decoder.has_value());
  drivers::CandumpReader reader(log);
  drivers::CandumpRecord r;
  Decoded out;
  while (reader.Next(&r)) {
    EXPECT_EQ(r.interface_name(), "can0");
    if (auto s = decoder->Decode(r.frame, r.t_ns)) out.samples.push_back(*s);
  }
  out.log = reader.counters();
  return out;
}

TEST(SimWheel, NoiseFreeFramesDecodeToTheTruthWithinTheLsb) {
  SimSetup setup = MakeSetup("aggressive", 3, 20.0);
  WheelSimConfig config = setup.wheel;
  config.noise.scale_error_left = config.noise.scale_error_right = 0.0;
  config.noise.speed_sigma_mps = 0.0;
  const std::vector<SimWheelSample> sim = SimulateWheels(*setup.trajectory, config, 3);
  ASSERT_NEAR(static_cast<double>(sim.size()), 20.0 * 50.0, 2.0);
  const Decoded d = ThroughCanLog(config, sim);
  ASSERT_EQ(d.samples.size(), sim.size());
  EXPECT_EQ(d.log.malformed_lines, 0u);
  for (size_t i = 0; i < sim.size(); ++i) {
    EXPECT_NEAR(d.samples[i].linear_velocity_mps, sim[i].v_base_mps.x(), 0.5e-3 + 1e-9);
    EXPECT_NEAR(d.samples[i].yaw_rate_radps, sim[i].yaw_rate_radps, 1e-3 / 0.5 + 1e-9);
    // candump keeps microseconds; the host received it 1–3 ms after the reading.
    EXPECT_EQ(d.samples[i].t_ns, 100 * kNsPerSec + sim[i].t_rx_ns / 1000 * 1000);
    const int64_t latency_ns = sim[i].t_rx_ns - sim[i].t_true_ns;
    EXPECT_GE(latency_ns, kNsPerMs);
    EXPECT_LE(latency_ns, 3 * kNsPerMs);
  }
}

/// Default noise: each wheel (1 + e)·v + N(0, σ²), so the decoded speed's error is
/// v·(e_l + e_r)/2 (a scale error) plus white noise of σ/√2, and the yaw rate's white part σ√2/b.
TEST(SimWheel, NoisyFramesMatchTheTruthWithinTheNoiseModel) {
  const SimSetup setup = MakeSetup("loop943", 4, 300.0);
  const WheelSimConfig& config = setup.wheel;
  const WheelNoiseModel& n = config.noise;
  EXPECT_NE(n.scale_error_left, n.scale_error_right) << "drawn per seed";
  EXPECT_LT(std::abs(n.scale_error_left), 4.0 * n.scale_error_sigma);
  const std::vector<SimWheelSample> sim = SimulateWheels(*setup.trajectory, config, 4);
  const Decoded d = ThroughCanLog(config, sim);
  ASSERT_EQ(d.samples.size(), sim.size());
  const double mean_scale = 0.5 * (n.scale_error_left + n.scale_error_right);
  const double diff_scale = n.scale_error_right - n.scale_error_left;
  double sum_v2 = 0.0, sum_w2 = 0.0;
  for (size_t i = 0; i < sim.size(); ++i) {
    const double v = sim[i].v_base_mps.x(), w = sim[i].yaw_rate_radps;
    const double half_b = 0.5 * config.track_width_m;
    // Scale errors remove: v_m = v(1 + ē) + ω b/2 Δe/2,  ω_m = ω(1 + ē) + v Δe / b.
    const double v_expected = v * (1.0 + mean_scale) + w * half_b * 0.5 * diff_scale;
    const double w_expected = w * (1.0 + mean_scale) + v * diff_scale / config.track_width_m;
    sum_v2 += std::pow(d.samples[i].linear_velocity_mps - v_expected, 2);
    sum_w2 += std::pow(d.samples[i].yaw_rate_radps - w_expected, 2);
  }
  const double count = static_cast<double>(sim.size());
  const double rms_v = std::sqrt(sum_v2 / count), rms_w = std::sqrt(sum_w2 / count);
  const double sigma_v = n.speed_sigma_mps / std::sqrt(2.0);
  const double sigma_w = n.speed_sigma_mps * std::sqrt(2.0) / config.track_width_m;
  std::printf("[ wheel ] %zu frames, white error RMS %.4f m/s (σ %.4f), %.4f rad/s (σ %.4f)\n",
              sim.size(), rms_v, sigma_v, rms_w, sigma_w);
  EXPECT_GT(rms_v, 0.8 * sigma_v);
  EXPECT_LT(rms_v, 1.2 * sigma_v);
  EXPECT_GT(rms_w, 0.8 * sigma_w);
  EXPECT_LT(rms_w, 1.2 * sigma_w);
}

TEST(SimWheel, FramesUseTheConfiguredLayout) {
  WheelSimConfig config;
  const drivers::CanFrame f = EncodeWheelFrame(config, -1.234, 40.0);  // 40 m/s saturates
  EXPECT_EQ(f.id, 0x201u);
  EXPECT_EQ(f.dlc, 8);
  EXPECT_FALSE(f.extended);
  EXPECT_EQ(static_cast<int16_t>(f.data[0] | f.data[1] << 8), -1234);
  EXPECT_EQ(static_cast<int16_t>(f.data[2] | f.data[3] << 8), 32767);
  EXPECT_TRUE(WheelCanConfig(config).ValidateLayout().empty());
}

}  // namespace
}  // namespace swlio::sim

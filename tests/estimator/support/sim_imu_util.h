#pragma once
/// @file
/// Test helpers: simulated IMU samples as estimator inputs, and true states from the route.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/imu_sim.h"
#include "swlio/core/time.h"
#include "swlio/core/types.h"

namespace swlio::test {

/// Switches off every noise source (white noise, bias walk, initial biases).
inline void MakeNoiseFree(sim::SimSetup& setup) {
  setup.imu.noise.acc_noise_density = 0.0;
  setup.imu.noise.gyro_noise_density = 0.0;
  setup.imu.noise.acc_bias_random_walk = 0.0;
  setup.imu.noise.gyro_bias_random_walk = 0.0;
  setup.imu.noise.acc_bias_initial_sigma = 0.0;
  setup.imu.noise.gyro_bias_initial_sigma = 0.0;
}

/// The samples stamped with their true sampling time.
inline std::vector<ImuSample> ToImuSamples(const std::vector<sim::SimImuSample>& sim) {
  std::vector<ImuSample> out;
  out.reserve(sim.size());
  for (const sim::SimImuSample& s : sim) {
    ImuSample o;
    o.t_ns = s.t_true_ns;
    o.acc_mps2 = s.acc_mps2;
    o.gyro_radps = s.gyro_radps;
    out.push_back(o);
  }
  return out;
}

/// True state (pose and velocity) at t_ns; biases left at zero.
inline State TrueState(const sim::Trajectory& trajectory, int64_t t_ns) {
  const sim::Kinematics k = trajectory.At(NsToSec(t_ns));
  State s;
  s.t_ns = t_ns;
  s.T_world_imu.linear() = k.R_world_body;
  s.T_world_imu.translation() = k.p_world;
  s.vel_world = k.v_world;
  return s;
}

}  // namespace swlio::test

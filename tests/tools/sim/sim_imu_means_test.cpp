// The simulated MTi's samples are what the device outputs (sensors/imu_sim.h): the means of the
// rate and of the specific force over each output interval, which keep a vibration faster than
// the output rate in their integrals.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "disturb/apply_disturbances.h"
#include "disturb/disturbance_manifest.h"
#include "scenarios/sim_setup.h"
#include "sensors/imu_sim.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::sim {
namespace {

TEST(SimImuMeans, SamplesAreTheMeansOverTheirIntervalsOfAVibratingMotion) {
  auto setup = MakeSimSetup("short", 5, 12.0);
  ApplyDisturbances(&*setup, *ParseDisturbanceList("vibration", nullptr));
  setup->imu.noise = ImuNoiseModel{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const Trajectory& tr = *setup->trajectory;
  const std::vector<SimImuSample> imu = SimulateImu(tr, setup->imu, 5);
  const Eigen::Vector3d gravity(0.0, 0.0, setup->imu.gravity_mps2);
  double max_rate = 0.0, max_force = 0.0, sq_instant = 0.0;
  size_t n = 0;
  for (size_t k = 1; k < imu.size(); k += 7) {
    const double t0 = NsToSec(imu[k - 1].t_true_ns), t1 = NsToSec(imu[k].t_true_ns);
    if (t0 < 0.5 || t1 > 11.5) continue;
    const Kinematics k0 = tr.At(t0), k1 = tr.At(t1);
    // The exact turn and velocity change over the interval, as means.
    const Eigen::Vector3d turn = lie::Log(k0.R_world_body.transpose() * k1.R_world_body);
    const Eigen::Matrix3d R_mid = k0.R_world_body * lie::Exp(0.5 * turn);
    const Eigen::Vector3d force =
        R_mid.transpose() * (k1.v_world - k0.v_world + gravity * (t1 - t0)) / (t1 - t0);
    max_rate = std::max(max_rate, (imu[k].gyro_radps - turn / (t1 - t0)).norm());
    max_force = std::max(max_force, (imu[k].acc_mps2 - force).norm());
    // What an instantaneous sample at the stamp would read instead.
    const Eigen::Vector3d instant = k1.R_world_body.transpose() * (k1.a_world + gravity);
    sq_instant += (instant - force).squaredNorm();
    ++n;
  }
  const double rms_instant = std::sqrt(sq_instant / static_cast<double>(n));
  std::cout << "largest error of the means: rate " << max_rate << " rad/s, force " << max_force
            << " m/s²; an instantaneous sample differs by " << rms_instant << " m/s² RMS\n";
  ASSERT_GT(n, 400u);
  EXPECT_LT(max_rate, 1e-6);  // the turn is taken exactly (stamps rounded to 1 ns)
  // The specific force by 2 kHz midpoint steps: (ωh)²/24 of a 80 Hz tone at most, 0.3 %.
  EXPECT_LT(max_force, 0.01);
  // The vibration's tones move an instantaneous value far more than that within an interval.
  EXPECT_GT(rms_instant, 10.0 * max_force);
}

}  // namespace
}  // namespace swlio::sim

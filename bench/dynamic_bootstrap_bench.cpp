// DynamicBootstrap from the first sweep to kReady (dynamic_bootstrap.h): 21 simulated RS16
// sweeps of the `aggressive` slalom (seed 3, from 20 s, 1.5 m/s) with the 400 Hz simulated IMU.
// The simulator's labelled sweeps are perfectly de-skewed; they are "re-skewed" here with the
// true pose at each point's own time, so the bootstrap sees what the scan assembler delivers.
// Time per item = per sweep (de-skew, front end, one or two registrations, the alignment).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/imu_sim.h"
#include "sensors/labelled_scan.h"
#include "swlio/core/time.h"
#include "swlio/estimator/init/dynamic_bootstrap.h"

namespace {

using namespace swlio::estimator;  // NOLINT(google-build-using-namespace): bench file only

struct Input {
  std::vector<swlio::Scan> sweeps;
  std::vector<swlio::ImuSample> imu;
  DynamicBootstrapConfig config;
};

Eigen::Isometry3d TrueLidarPose(const swlio::sim::SimSetup& setup, int64_t t_ns) {
  const swlio::sim::Kinematics k = setup.trajectory->At(swlio::NsToSec(t_ns));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = k.R_world_body;
  T.translation() = k.p_world;
  return T * setup.lidar.T_imu_lidar;
}

Input MakeInput() {
  auto setup = swlio::sim::MakeSimSetup("aggressive", 3, 23.0);
  if (!setup) std::abort();
  Input in;
  in.config.odometry.T_imu_lidar = setup->lidar.T_imu_lidar;
  swlio::sim::LabelledScanSource source(*setup);
  swlio::sim::LabelledScan ls;
  for (int k = 0; k < 21 && source.Next(&ls, 20.0); ++k) {
    for (swlio::LidarPoint& p : ls.scan.points) {  // back to each point's own time
      const Eigen::Isometry3d T_i_end =
          TrueLidarPose(*setup, ls.scan.t_start_ns + p.dt_ns).inverse() * ls.T_world_lidar_end;
      p.xyz_m = (T_i_end * p.xyz_m.cast<double>()).cast<float>();
    }
    in.sweeps.push_back(ls.scan);
  }
  for (const swlio::sim::SimImuSample& s :
       swlio::sim::SimulateImu(*setup->trajectory, setup->imu, 3)) {
    if (s.t_true_ns < swlio::SecToNs(19.5)) continue;
    in.imu.push_back({s.t_true_ns, s.acc_mps2, s.gyro_radps});
  }
  return in;
}

void BM_DynamicBootstrapToReady(benchmark::State& state) {
  static const Input in = MakeInput();
  int ready = 0;
  for (auto _ : state) {
    DynamicBootstrap boot(in.config);
    size_t next = 0;
    for (const swlio::Scan& scan : in.sweeps) {
      for (; next < in.imu.size() && in.imu[next].t_ns <= scan.t_end_ns + 5'000'000; ++next) {
        boot.AddImu(in.imu[next]);
      }
      if (boot.AddScan(scan) == BootstrapStatus::kReady) ++ready;
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.sweeps.size()));
  state.counters["ready_runs"] = ready;
}
BENCHMARK(BM_DynamicBootstrapToReady)->Unit(benchmark::kMillisecond);

}  // namespace

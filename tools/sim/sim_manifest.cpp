// manifest.yaml of a simulated recording: every fact needed to interpret the files and to
// judge an estimate (true extrinsic, clocks, noise), written as plain YAML text.

#include <cinttypes>
#include <cstdio>
#include <sstream>

#include "sim_recording.h"
#include "swlio/core/lie.h"

namespace swlio::sim {
namespace {

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

template <typename Range>
std::string List(const Range& values) {
  std::string s = "[";
  for (const auto& v : values) s += (s.size() > 1 ? ", " : "") + Num(v);
  return s + "]";
}

}  // namespace

std::string ManifestYaml(const SimSetup& setup,
                         const RecordingStats& stats,
                         int64_t host_start_ns,
                         const std::string& mode) {
  const Eigen::Isometry3d& T = setup.lidar.T_imu_lidar;
  const Eigen::Quaterniond q = lie::PositiveW(Eigen::Quaterniond(T.linear()));
  const Eigen::Vector3d rpy_deg = lie::RpyFromRotation(T.linear()) * 180.0 / 3.14159265358979323846;
  const Eigen::Vector3d t = T.translation();
  const ImuNoiseModel& n = setup.imu.noise;
  std::ostringstream y;
  y << "# swlio simulated recording\n"
    << "format_version: 1\n"
    << "mode: " << mode << "\n"
    << "scenario: " << setup.scenario.name << "\n"
    << "description: \"" << setup.scenario.description << "\"\n"
    << "seed: " << setup.seed << "\n"
    << "world_seed: " << setup.world_seed << "\n"
    << "duration_s: " << Num(SimDuration(setup)) << "\n"
    << "path_length_m: " << Num(setup.trajectory->length_m()) << "\n"
    << "# Host time (ns, CLOCK_MONOTONIC-like) of simulation time 0. pcap record times and\n"
    << "# imu.rx.csv are host receive times; groundtruth.tum stamps are host times of the pose.\n"
    << "host_start_ns: " << host_start_ns << "\n"
    << "extrinsic_T_imu_lidar:  # maps LiDAR points (RoboSense manual frame) into the IMU frame\n"
    << "  translation_m: " << List(std::array{t.x(), t.y(), t.z()}) << "\n"
    << "  quaternion_xyzw: " << List(std::array{q.x(), q.y(), q.z(), q.w()}) << "\n"
    << "  rotation_rpy_deg: " << List(std::array{rpy_deg.x(), rpy_deg.y(), rpy_deg.z()})
    << "  # R = Rz(yaw) Ry(pitch) Rx(roll)\n"
    << "lidar:\n"
    << "  model: rs16\n"
    << "  rpm: " << Num(setup.lidar.rpm) << "\n"
    << "  msop_port: " << setup.lidar.msop_port << "\n"
    << "  difop_port: " << setup.lidar.difop_port << "\n"
    << "  vertical_angles_deg_by_channel: " << List(setup.lidar.vertical_angles_deg) << "\n"
    << "  range_sigma_m: " << Num(setup.lidar.range_sigma_m) << "\n"
    << "  min_range_m: " << Num(setup.lidar.min_range_m) << "\n"
    << "  max_range_m: " << Num(setup.lidar.max_range_m) << "\n"
    << "  # header_time_s = (1 + drift_ppm·1e-6)·(host_s − host_start_s) + offset_s\n"
    << "  clock: {offset_s: " << Num(setup.lidar.clock.offset_s)
    << ", drift_ppm: " << Num(setup.lidar.clock.drift_ppm) << "}\n"
    << "imu:\n"
    << "  model: MTi-G-710 (simulated)\n"
    << "  rate_hz: " << Num(setup.imu.rate_hz) << "\n"
    << "  items: [PacketCounter, SampleTimeFine, Acceleration, RateOfTurn]  # Float32\n"
    << "  gravity_mps2: " << Num(setup.imu.gravity_mps2) << "\n"
    << "  acc_noise_density_mps2_per_sqrthz: " << Num(n.acc_noise_density) << "\n"
    << "  gyro_noise_density_radps_per_sqrthz: " << Num(n.gyro_noise_density) << "\n"
    << "  acc_bias_random_walk_mps3_per_sqrthz: " << Num(n.acc_bias_random_walk) << "\n"
    << "  gyro_bias_random_walk_radps2_per_sqrthz: " << Num(n.gyro_bias_random_walk) << "\n"
    << "  acc_bias_initial_sigma_mps2: " << Num(n.acc_bias_initial_sigma) << "\n"
    << "  gyro_bias_initial_sigma_radps: " << Num(n.gyro_bias_initial_sigma) << "\n"
    << "  # SampleTimeFine (10 kHz ticks) = (1 + drift_ppm·1e-6)·(host_s − host_start_s) + "
       "offset_s\n"
    << "  clock: {offset_s: " << Num(setup.imu.clock.offset_s)
    << ", drift_ppm: " << Num(setup.imu.clock.drift_ppm) << "}\n"
    << "  serial: {baud: " << Num(setup.imu.baud)
    << ", burst_period_s: " << Num(setup.imu.delivery.burst_period_s)
    << ", stall_probability: " << Num(setup.imu.delivery.stall_probability)
    << ", stall_s: " << Num(setup.imu.delivery.stall_s) << "}\n"
    << "groundtruth_rate_hz: " << Num(setup.gt_rate_hz) << "\n"
    << "counts:\n"
    << "  msop_packets: " << stats.msop_packets << "\n"
    << "  difop_packets: " << stats.difop_packets << "\n"
    << "  valid_returns: " << stats.valid_returns << "\n"
    << "  imu_frames: " << stats.imu_frames << "\n"
    << "  groundtruth_poses: " << stats.gt_poses << "\n"
    << "files: {lidar: lidar.pcap, imu: imu.xbus, imu_rx: imu.rx.csv, "
       "groundtruth: groundtruth.tum}\n";
  return y.str();
}

}  // namespace swlio::sim

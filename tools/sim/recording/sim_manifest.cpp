// manifest.yaml of a simulated recording: every fact needed to interpret the files and to
// judge an estimate (true extrinsic, clocks, noise), written as plain YAML text.

#include <cinttypes>
#include <cstdio>
#include <sstream>
#include <vector>

#include "disturb/disturbance_manifest.h"
#include "recording/sim_recording.h"
#include "swlio/core/exact_number.h"
#include "swlio/core/lie.h"
#include "swlio/drivers/recording_format.h"

namespace swlio::sim {
namespace {

/// Every number exactly (shortest round trip): other programs read them.
std::string Num(double v) { return ExactNumber(v); }

template <typename Range>
std::string List(const Range& values) {
  std::string s = "[";
  for (const auto& v : values) s += (s.size() > 1 ? ", " : "") + Num(v);
  return s + "]";
}

template <typename Range>
std::string Nested(const Range& lists) {
  std::string s = "[";
  for (const auto& l : lists) s += (s.size() > 1 ? ", " : "") + List(l);
  return s + "]";
}

/// `gnss:` (absent with --no-gnss). Keys unique in the file: readers match lines by key.
std::string GnssBlock(const SimSetup& setup) {
  if (setup.imu.gnss_pvt_period_s <= 0.0) return "";
  const GnssSimConfig& g = setup.gnss;
  const GnssErrorModel& n = g.noise;
  std::vector<std::array<double, 2>> outages;
  for (const TimeWindow& w : g.outages) outages.push_back({w.start_s, w.duration_s});
  std::vector<std::array<double, 3>> jumps;
  for (const GnssJump& j : g.jumps) jumps.push_back({j.start_s, j.duration_s, j.east_m});
  const Eigen::Vector3d& b = g.p_imu_antenna_m;
  std::ostringstream y;
  y << "gnss:  # GnssPvtData (u-blox NAV-PVT) items in imu.xbus; world = ENU at the origin\n"
    << "  origin_lat_deg: " << Num(g.origin.lat_deg) << "\n"
    << "  origin_lon_deg: " << Num(g.origin.lon_deg) << "\n"
    << "  origin_height_m: " << Num(g.origin.height_m) << "  # WGS-84 ellipsoidal\n"
    << "  antenna_imu_m: " << List(std::array{b.x(), b.y(), b.z()})
    << "  # lever arm p_imu_antenna, IMU frame\n"
    << "  rate_hz: " << Num(1.0 / setup.imu.gnss_pvt_period_s) << "\n"
    << "  first_fix_s: " << Num(setup.imu.gnss_first_fix_s) << "\n"
    << "  # errors: first-order Gauss-Markov per axis (east, north: sigma_h; up: sigma_v)\n"
    << "  sigma_h_m: " << Num(n.sigma_h_m) << "\n"
    << "  sigma_v_m: " << Num(n.sigma_v_m) << "\n"
    << "  correlation_time_s: " << Num(n.correlation_time_s) << "\n"
    << "  velocity_sigma_mps: " << Num(n.velocity_sigma_mps) << "\n"
    << "  reported_accuracy_inflation: " << Num(n.accuracy_inflation)
    << "  # hAcc = k*sqrt(2)*sigma_h, vAcc = k*sigma_v\n"
    << "  outages_s: " << Nested(outages) << "  # [start, duration]: fixType 0\n"
    << "  jumps: " << Nested(jumps) << "  # [start_s, duration_s, east_m]: outliers\n";
  return y.str();
}

/// `wheel:` (file recordings with can.log only).
std::string WheelBlock(const SimSetup& setup, const std::string& mode) {
  if (!setup.wheel.enabled || mode != "file") return "";
  const WheelSimConfig& w = setup.wheel;
  const Eigen::Vector3d t = w.T_imu_base.translation();
  const Eigen::Quaterniond q = lie::PositiveW(Eigen::Quaterniond(w.T_imu_base.linear()));
  char id[16];
  std::snprintf(id, sizeof id, "0x%03X", w.can_id);
  std::ostringstream y;
  y << "wheel:  # chassis wheel odometry in can.log (candump), differential drive\n"
    << "  # base frame: x forward, y left, z up, on the ground midway between the wheels\n"
    << "  T_imu_base_translation_m: " << List(std::array{t.x(), t.y(), t.z()}) << "\n"
    << "  T_imu_base_quaternion_xyzw: " << List(std::array{q.x(), q.y(), q.z(), q.w()}) << "\n"
    << "  track_width_m: " << Num(w.track_width_m) << "\n"
    << "  rate_hz: " << Num(w.rate_hz) << "\n"
    << "  can_mode: wheel_speeds\n  can_wheel_speed_unit: mps\n"
    << "  can_frame_id: " << id << "\n  can_dlc: 8\n"
    << "  can_left_byte_offset: 0  # int16, intel byte order, signed\n"
    << "  can_right_byte_offset: 2\n"
    << "  can_scale_mps_per_lsb: " << Num(w.scale_mps_per_lsb) << "\n"
    << "  scale_error_left: " << Num(w.noise.scale_error_left) << "  # measured = (1 + e) true\n"
    << "  scale_error_right: " << Num(w.noise.scale_error_right) << "\n"
    << "  speed_sigma_mps: " << Num(w.noise.speed_sigma_mps) << "\n"
    << "  latency_s: " << List(std::array{w.noise.latency_min_s, w.noise.latency_max_s})
    << "  # host receive time - reading, uniform\n";
  return y.str();
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
    << "# format_version 2: LiDAR points and extrinsic_T_imu_lidar in the LiDAR vendor driver's\n"
    << "# frame (x forward, y left, z up), rays from the lens centre; version 1 (before swlio\n"
    << "# issue 32) used the RoboSense manual's frame and no lens offset, and is refused.\n"
    << "format_version: " << drivers::kRecordingFormatVersion << "\n"
    << "mode: " << mode << "\n"
    << "scenario: " << setup.scenario.name << "\n"
    << "description: \"" << setup.scenario.description << "\"\n"
    << "seed: " << setup.seed << "\n"
    << "world_seed: " << setup.world_seed << "\n"
    << "duration_s: " << Num(SimDuration(setup)) << "\n"
    << "path_length_m: " << Num(setup.trajectory->DrivenLengthM()) << "  # in duration_s\n"
    << "# Host time (ns, CLOCK_MONOTONIC-like) of simulation time 0. pcap record times and\n"
    << "# imu.rx.csv are host receive times; groundtruth.tum stamps are host times of the pose.\n"
    << "host_start_ns: " << host_start_ns << "\n"
    << "extrinsic_T_imu_lidar:  # LiDAR points (x forward, y left, z up) into the IMU frame\n"
    << "  translation_m: " << List(std::array{t.x(), t.y(), t.z()}) << "\n"
    << "  quaternion_xyzw: " << List(std::array{q.x(), q.y(), q.z(), q.w()}) << "\n"
    << "  rotation_rpy_deg: " << List(std::array{rpy_deg.x(), rpy_deg.y(), rpy_deg.z()})
    << "  # R = Rz(yaw) Ry(pitch) Rx(roll)\n"
    << "lidar:\n"
    << "  model: rs16\n"
    << "  rpm: " << Num(setup.lidar.rpm) << "\n"
    << "  msop_port: " << setup.lidar.msop_port << "\n"
    << "  difop_port: " << setup.lidar.difop_port << "\n"
    << "  lens_offset_m: " << Num(setup.lidar.lens_offset_m) << "  # rays start at the lens\n"
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
    << (setup.imu.gnss_pvt_period_s > 0.0
            ? "  # plus GnssPvtData in the first message of each GNSS epoch (gnss: below)\n"
            : "")
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
    << GnssBlock(setup) << WheelBlock(setup, mode) << DisturbanceManifestBlock(setup)
    << "groundtruth_rate_hz: " << Num(setup.gt_rate_hz) << "\n"
    << "counts:\n"
    << "  msop_packets: " << stats.msop_packets << "\n"
    << "  difop_packets: " << stats.difop_packets << "\n"
    << "  valid_returns: " << stats.valid_returns << "\n"
    << "  imu_frames: " << stats.imu_frames << "\n"
    << "  groundtruth_poses: " << stats.gt_poses << "\n"
    << "  gnss_items: " << stats.gnss_items << "\n"
    << "  gnss_no_fix: " << stats.gnss_no_fix << "\n"
    << "  wheel_frames: " << stats.wheel_frames << "\n"
    << "files: {lidar: lidar.pcap, imu: imu.xbus, imu_rx: imu.rx.csv, "
    << (WheelBlock(setup, mode).empty() ? "" : "can: can.log, wheel_truth: wheel_truth.csv, ")
    << "groundtruth: groundtruth.tum}\n";
  return y.str();
}

}  // namespace swlio::sim

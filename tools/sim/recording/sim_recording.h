#pragma once
/// @file
/// Writes a simulated run as a recording folder, the same files the daemon's recorder writes:
///   lidar.pcap       MSOP/DIFOP packets (UDP to 127.0.0.1), record time = host receive time
///   imu.xbus         raw Xbus bytes as the serial port delivers them (MTData2, MID 0x36)
///   imu.rx.csv       host receive time of each serial burst: byte_offset,bytes,t_rx_ns
///   can.log          wheel-speed CAN frames, candump log format, host receive times
///   wheel_truth.csv  true base speed and yaw rate of each wheel frame: t_ns,v_x_mps,yaw_rate_radps
///   groundtruth.tum  IMU body frame in the world frame, host time (s), TUM format
///   manifest.yaml    scenario, seed, true extrinsic, clocks, sensor settings, counts
///   actors.csv       people and vehicles at 10 Hz (only with them on: recording/actors_csv.h)
/// imu.xbus carries GnssPvtData in the messages of the GNSS epochs (gnss_sim.h) unless
/// imu.gnss_pvt_period_s is 0; can.log and wheel_truth.csv are left out when !wheel.enabled.
/// Host times of a file recording start at kFileHostStartNs.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "scenarios/sim_setup.h"

namespace swlio::sim {

inline constexpr int64_t kFileHostStartNs = 100'000'000'000;  ///< host time 100 s at sim t = 0

struct RecordingStats {
  uint64_t msop_packets = 0;
  uint64_t difop_packets = 0;
  uint64_t imu_frames = 0;
  uint64_t gt_poses = 0;
  uint64_t valid_returns = 0;
  uint64_t gnss_items = 0;    ///< GnssPvtData items in imu.xbus
  uint64_t gnss_no_fix = 0;   ///< of them, with fixType 0 (outages)
  uint64_t wheel_frames = 0;  ///< lines in can.log
};

/// One MTData2 frame (PacketCounter, SampleTimeFine, Acceleration, RateOfTurn; Float32) for
/// `sample`, plus GnssPvtData when `gnss_pvt` is given. Returns the frame size (0 when `out`
/// is too small).
size_t EncodeImuFrame(const SimImuSample& sample,
                      std::span<uint8_t> out,
                      const drivers::xsens::XsensGnssPvt* gnss_pvt = nullptr);

/// The GnssPvtData of sample `index` from `fixes` (ordered by imu_index), advancing `*next`
/// past it; nullptr when that sample carries none.
const drivers::xsens::XsensGnssPvt* PvtForSample(const std::vector<SimGnssFix>& fixes,
                                                 size_t index,
                                                 size_t* next);

/// Writes the folder (created if needed). Returns false with `error` on an I/O failure.
bool WriteRecording(const SimSetup& setup,
                    const std::filesystem::path& dir,
                    RecordingStats* stats,
                    std::string* error);

/// TUM line "t tx ty tz qx qy qz qw" of the IMU pose at sim time `t_s`, stamped `host_ns`.
std::string TumLine(const SimSetup& setup, double t_s, int64_t host_ns);

/// The manifest text (YAML).
std::string ManifestYaml(const SimSetup& setup,
                         const RecordingStats& stats,
                         int64_t host_start_ns,
                         const std::string& mode);

}  // namespace swlio::sim

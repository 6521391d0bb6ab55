#pragma once
/// @file
/// Version of a recording folder (lidar.pcap, imu.xbus, imu.rx.csv, manifest.yaml) as
/// swliod --record and swlio-sim write it and the daemon's RecordingReader reads it: the
/// manifest's `format_version:` line.
///
/// 2 (issue 32): LiDAR returns decode in the vendor driver's frame (x forward, y left, z up,
/// lidar_decoder.h), so the manifest's extrinsic_T_imu_lidar is in that frame; the simulator
/// casts its rays from the lens centre. 1: the RoboSense manual's frame (y forward, x right),
/// no lens offset; such a recording is refused (ManifestVersionProblem), never read in the
/// wrong frame.

#include <cstdint>

namespace swlio::drivers {

inline constexpr int64_t kRecordingFormatVersion = 2;

}  // namespace swlio::drivers

#pragma once
/// @file
/// Opens what swlio-run and swlio-replay are given: a recording folder (recording_reader.h:
/// one with manifest.yaml, lidar.pcap or imu.xbus) or else a ROS bag (bag_input.h).

#include <memory>
#include <string>

#include "swlio/daemon/recording/bag_input.h"
#include "swlio/daemon/recording/recording_reader.h"

namespace swlio::daemon {

/// How to read either kind of input; each kind looks only at its own options.
struct SensorInputOptions {
  RecordingReadOptions recording;
  BagInputOptions bag;
};

/// The input at `path`; nullptr with `error` as the reader of its kind says. A recording is
/// read on the UDP ports its manifest names (WithManifestPorts).
std::unique_ptr<SensorInput> OpenSensorInput(const std::string& path,
                                             const drivers::LidarConfig& lidar,
                                             const drivers::ImuConfig& imu,
                                             const SensorInputOptions& options,
                                             std::string* error);

}  // namespace swlio::daemon

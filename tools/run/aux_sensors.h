#pragma once
/// @file
/// swlio-run's optional sensors (`--wheel on`, `--gnss on`): what the input must return, and
/// the estimator's settings for them. A recording describes its own rig, so its manifest's
/// wheel and GNSS blocks (the chassis frame and CAN layout; the ENU origin and the antenna's
/// lever arm) win over the configuration file, as its extrinsic does. A bag has no manifest:
/// its wheel and GNSS topics are read with the configuration's frames and origin.

#include <filesystem>
#include <string>

#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/recording/input_open.h"

namespace swlio::tools {

/// Turns wheel odometry (the window's velocity factor) and GNSS (the pose graph's position
/// factor) on in `config` and asks `read` for their streams. False with `*error` when a
/// recording's CAN layout is neither in its manifest nor a valid one in the configuration.
bool SetUpAuxSensors(const std::filesystem::path& dir,
                     bool wheel,
                     bool gnss,
                     daemon::DaemonConfig* config,
                     daemon::SensorInputOptions* read,
                     std::string* error);

}  // namespace swlio::tools

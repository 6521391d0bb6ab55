#pragma once
/// @file
/// A DaemonConfig as YAML: `swliod --print-config` (the effective configuration).
///
/// Every key of config/swlio.yaml with its value, defaults filled in, under the same names and
/// in the same structure, so that LoadConfigText() reads it back into the same DaemonConfig:
/// numbers are written in the shortest form that reads back as the same double, angles and
/// other units as the keys name them. Keys whose default is "absent" (the GNSS origin) are left
/// out when absent. Paths are written as the config holds them: the loader has made relative
/// ones absolute (against the file's directory, or the current directory for standard input).

#include <string>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {

/// `config` as a YAML document. Meant for a configuration that passed Validate(): a value no
/// key can hold (a NaN) is written as such and refused when read back.
std::string PrintConfig(const DaemonConfig& config);

}  // namespace swlio::daemon

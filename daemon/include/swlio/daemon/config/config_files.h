#pragma once
/// @file
/// Checks of the files a loaded configuration names. The loader only parses and validates
/// values; `swliod --check-config` and start-up also need the referenced files to be usable.

#include <string>
#include <vector>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {

/// Problems with the files `config` names, one readable sentence each (empty when none):
/// ipc.dds_config_file must be readable and, with ipc.require_loopback, loopback-only (the
/// same rule ipc::Participant::Create enforces). Paths are used as given (the loader has
/// already resolved relative ones against the config file's directory).
std::vector<std::string> CheckReferencedFiles(const DaemonConfig& config);

}  // namespace swlio::daemon

#pragma once
/// @file
/// Logging set-up: one spdlog logger writing to rotating files and to stderr (which journald
/// collects under systemd), configured from LoggingConfig.

#include <memory>
#include <string>

#include <spdlog/logger.h>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {

/// The lines' pattern: ISO-8601 local time with ms, level, thread id, message (enough to line
/// logs up with recordings). The black box's log.txt uses it too.
inline constexpr const char* kLogPattern = "%Y-%m-%dT%H:%M:%S.%e%z %-5l [%t] %v";

/// Creates the logger named "swlio" (and makes it spdlog's default). Creates the log directory
/// when missing. Returns nullptr and fills `error` when the file cannot be opened.
std::shared_ptr<spdlog::logger> SetupLogging(const LoggingConfig& config, std::string* error);

}  // namespace swlio::daemon

#pragma once
/// @file
/// Logging set-up: one spdlog logger writing to rotating files, to stderr, and (journal_sink.h)
/// to the systemd journal with structured fields, configured from LoggingConfig.

#include <memory>
#include <string>

#include <spdlog/logger.h>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {

/// The lines' pattern: ISO-8601 local time with ms, level, thread id, message (enough to line
/// logs up with recordings). The black box's log.txt uses it too.
inline constexpr const char* kLogPattern = "%Y-%m-%dT%H:%M:%S.%e%z %-5l [%t] %v";

/// Whether systemd started this process as a service, from its environment (systemd.exec(5),
/// "Environment variables in spawned processes"): `journal_stream` (JOURNAL_STREAM,
/// "<device>:<inode>") names `stderr_fd`, i.e. stderr goes to the journal; or `invocation_id`
/// (INVOCATION_ID) is set without JOURNAL_STREAM (a service whose output goes elsewhere).
/// A JOURNAL_STREAM naming another file is inherited, not ours (systemd.exec(5) says to compare
/// it with stderr): a shell in a desktop session or a CI job started by a service.
bool StartedBySystemd(const char* journal_stream, const char* invocation_id, int stderr_fd);

/// StartedBySystemd() with this process's environment and stderr.
bool StartedBySystemd();

/// Whether the journal sink is on: `config.journald` "true" or "false", or for "auto"
/// StartedBySystemd().
bool JournaldOn(const LoggingConfig& config);

/// stderr's level: `config.stderr_level`, or for "auto" "info", and "off" while the journal sink
/// is on (under systemd stderr goes to the journal as well: each line would be there twice).
std::string EffectiveStderrLevel(const LoggingConfig& config, bool journald_on);

/// Creates the logger named "swlio" (and makes it spdlog's default). Creates the log directory
/// when missing; adds the journal sink when JournaldOn(config). Returns nullptr and fills `error`
/// when the file cannot be opened.
std::shared_ptr<spdlog::logger> SetupLogging(const LoggingConfig& config, std::string* error);

}  // namespace swlio::daemon

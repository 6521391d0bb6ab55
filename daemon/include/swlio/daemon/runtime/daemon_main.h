#pragma once
/// @file
/// swliod's run loop on the main thread: starts the Runtime, waits for SIGTERM / SIGINT
/// (blocked in every thread, taken with sigtimedwait here), sends READY=1 once the sensors
/// stream and the estimator has a state, feeds the systemd watchdog only while every thread
/// progresses, and logs a status line every `logging.status_period_s`.

#include <cstdint>

#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/runtime/runtime.h"

namespace swlio::daemon {

/// Blocks SIGTERM, SIGINT and SIGHUP in the calling thread and every thread it starts later
/// (call first in main).
void BlockStopSignals();

/// Runs until a stop signal or `max_run_ns` (> 0: a time limit, for tests and the demo).
/// The time offset kept in `state.time_offset_file` starts the estimator and is saved as it
/// improves (time_offset_keeper.h). Returns the exit code.
int RunDaemon(const DaemonConfig& file_config, const RuntimeOptions& options, int64_t max_run_ns);

}  // namespace swlio::daemon

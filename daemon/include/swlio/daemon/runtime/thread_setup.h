#pragma once
/// @file
/// Applies RealtimeConfig to the calling thread (name, SCHED_FIFO priority, CPU pinning) and
/// to the process (mlockall). Failures (no CAP_SYS_NICE / CAP_IPC_LOCK, a CPU that does not
/// exist) come back as text for the log; the daemon runs on with normal scheduling.

#include <string>
#include <vector>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {

/// Names the calling thread (≤ 15 characters, shown by top -H / ps -L) and applies its entry
/// of `config.threads`: its nice value always, its SCHED_FIFO priority and CPU when
/// `config.enabled`. Returns the problems (empty when all applied).
std::vector<std::string> SetUpThisThread(const char* name, const RealtimeConfig& config);

/// mlockall(MCL_CURRENT | MCL_FUTURE) when `config.lock_memory`; the problem or empty.
std::string LockMemory(const RealtimeConfig& config);

}  // namespace swlio::daemon

#pragma once
/// @file
/// The daemon's whole configuration: one struct per module, aggregated. Loaded from YAML only
/// by config_loader.cpp; every field has an in-class default.

#include <cstdint>
#include <string>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/drivers/can_config.h"
#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/lidar_config.h"
#include "swlio/estimator/common/estimator_config.h"
#include "swlio/estimator/loop/loop_closure_config.h"
#include "swlio/estimator/map/localization_config.h"
#include "swlio/estimator/window/window_estimator_config.h"
#include "swlio/ipc/ipc_config.h"

namespace swlio::daemon {

/// Log output: rotating files, stderr, and the systemd journal with structured fields.
struct LoggingConfig {
  /// Directory of the rotating log files; relative paths are taken from the config file's
  /// directory. Empty disables file logging.
  std::string directory = "/var/log/swlio";
  std::string file_name = "swliod.log";
  std::string file_level = "info";    ///< trace, debug, info, warn, error, critical, off
  std::string stderr_level = "auto";  ///< same levels, or auto (below)
  int64_t max_file_size_mb = 20;      ///< rotate when a file reaches this size
  int64_t max_files = 10;             ///< rotated files kept
  double status_period_s = 5.0;       ///< period of the one-line status in the log
  /// Every log record to the journal with structured fields (sd_journal_sendv; SWLIO_EVENT,
  /// SWLIO_STATE, counters): "true", "false", or "auto": on when systemd started swliod
  /// (StartedBySystemd(): JOURNAL_STREAM names stderr, or INVOCATION_ID is set). While it is
  /// on, stderr_level "auto" means off (under systemd stderr goes to the journal too: each line
  /// would be there twice), else info.
  std::string journald = "auto";

  ConfigIssues Validate() const;
};

/// The black box (YAML `record`; docs/blackbox.md): the raw sensor bytes of the last minutes
/// in rotating segments, and incidents kept from them. Off unless the file turns it on (the
/// robot's config/swlio.yaml does; tests and the demo do not).
struct RecordConfig {
  bool ring = false;                                  ///< keep the rotating segments
  std::string directory = "/var/lib/swlio/blackbox";  ///< ring/ and incidents/ go here
  double ring_minutes = 10.0;                         ///< sensor time the ring spans
  double segment_s = 10.0;                            ///< one segment's span (rotation period)
  int64_t max_disk_mb = 2048;                         ///< the ring's segments, the open one too
  double incident_before_s = 120.0;  ///< an incident keeps this much before its first event
  double incident_after_s = 60.0;    ///< and this much after it
  int64_t incidents_max_count = 20;  ///< kept incidents; the oldest goes first, never the newest
  int64_t incidents_max_mb = 4096;   ///< their size on disk, likewise

  ConfigIssues Validate() const;
};

/// Scheduling of one daemon thread (YAML `realtime.threads[i]`).
struct ThreadSchedConfig {
  /// lidar_rx, imu_rx, can_rx, propagator, optimizer, publisher, recorder, loop_closure or
  /// localization
  std::string name;
  int64_t priority = 0;  ///< SCHED_FIFO priority 1–99; 0 keeps normal (SCHED_OTHER) scheduling
  int64_t cpu = -1;      ///< pin to this CPU; −1: any
  /// Nice value −20..19 under normal scheduling: for a thread without a SCHED_FIFO priority,
  /// or with one when `enabled` is false or SCHED_FIFO is refused (Linux nice is per thread).
  /// Below 0 it needs RLIMIT_NICE, which swliod.service grants down to −10 (LimitNICE), or
  /// CAP_SYS_NICE.
  int64_t nice = 0;
};

/// The schedule swliod runs with unless the YAML lists its own: the sensor-to-pose path
/// (lidar_rx, imu_rx, propagator, publisher) at SCHED_FIFO 80/80/70/60 (swliod.service allows
/// up to 80 with LimitRTPRIO, no capability), or at nice −10 where real-time scheduling is off
/// or refused, so that on a busy computer its threads, which sleep most of the time, run as
/// soon as they wake; the optimizer at nice 0, loop closure at nice 5 (docs/scheduling.md).
std::vector<ThreadSchedConfig> DefaultThreadSchedule();

/// Real-time options (YAML `realtime`). SCHED_FIFO is on by default: an unprivileged thread may
/// use it up to RLIMIT_RTPRIO (sched(7)), which swliod.service sets; a refusal is logged and
/// the thread keeps its nice value. CPU pinning above and memory locking need the drop-in
/// swliod-realtime.conf (CAP_SYS_NICE, LimitMEMLOCK).
struct RealtimeConfig {
  bool enabled = true;       ///< apply `threads`' SCHED_FIFO priorities and CPU pinning
  bool lock_memory = false;  ///< mlockall(MCL_CURRENT | MCL_FUTURE) once the threads run
  /// When the estimator runs this far behind the LiDAR (a sweep's last packet arrived longer
  /// ago, sensor time), it skips every other sweep until it has caught up, and longer runs
  /// (up to 4 in a row) the further behind it is (sweep_shedding.h); 0 never skips, and the
  /// packet queue overflows instead.
  double max_sweep_lag_s = 0.5;
  /// A `threads` list in the YAML replaces this one as a whole.
  std::vector<ThreadSchedConfig> threads = DefaultThreadSchedule();
  ConfigIssues Validate() const;
};

/// Saved maps (YAML `map`; estimator/map-format.md). The command line's --save-map, --map and
/// --localize set the same fields.
struct MapFilesConfig {
  /// With loop closure: the pose graph is saved here when the daemon stops (empty: not saved),
  /// with its merged cloud beside it (same path + ".pcd").
  std::string save_path;
  /// A saved map to localize in (needs `localize`).
  std::string load_path;
  /// Localize in `load_path` instead of building a map: relocalization from place descriptors,
  /// then tracking against the fixed map (estimator.localization); loop closure is off then.
  bool localize = false;

  ConfigIssues Validate() const;
};

/// What the daemon learns and keeps across restarts (YAML `state`; daemon/state/). Off unless
/// the file turns it on (the robot's config/swlio.yaml does; tests and the demo do not).
struct StateConfig {
  /// The LiDAR–IMU time offset estimated online (time_offset_keeper.h): the next start begins
  /// from it. Relative paths are taken from the config file's directory. Empty: not kept.
  std::string time_offset_file;
  /// A newer estimate is written at most this often (s); and always when the daemon stops.
  double save_period_s = 60.0;

  ConfigIssues Validate() const;
};

/// The control socket swlioctl talks to (YAML `control`; docs/control.md).
struct ControlConfig {
  /// UNIX stream socket path; relative paths are taken from the config file's directory.
  /// Empty: no control socket. The default lies in /run/swlio (swlio.tmpfiles.conf);
  /// where it cannot be created (swliod run by hand), the daemon logs why and runs on without.
  std::string socket = "/run/swlio/swliod.sock";
  /// The socket's group (mode 0660): the operators who may use swlioctl besides the daemon's
  /// user. Empty: the daemon's own group. swlio.sysusers.conf creates swlio-operators.
  std::string group = "swlio-operators";
  /// A client must send its whole request line within this time, and read the reply within
  /// it, or it is dropped (s).
  double request_timeout_s = 2.0;
  /// save-map and reset run on the thread that owns the graph or the estimator; the reply
  /// waits this long for them (s), then says "timeout" (the command may still complete).
  double command_timeout_s = 60.0;
  /// Connections served at once; one more is answered "busy" and closed.
  int64_t max_clients = 8;

  ConfigIssues Validate() const;
};

/// Version of the configuration schema this build reads (`config_version` in the file).
inline constexpr int64_t kConfigVersion = 1;

struct DaemonConfig {
  int64_t config_version = kConfigVersion;
  drivers::LidarConfig lidar;
  drivers::ImuConfig imu;
  drivers::CanConfig can;
  estimator::EstimatorConfig estimator;
  /// The tightly coupled window's own options (YAML `estimator.window`). Its `odometry` and
  /// `bootstrap.odometry` are not read from the file: the user builds them from `estimator` and
  /// the extrinsic (swlio-run does), so they are not validated here either.
  estimator::WindowEstimatorConfig window;
  /// Loop closure and the pose graph (YAML `estimator.loop_closure`).
  estimator::LoopClosureConfig loop_closure;
  /// Localization in a saved map (YAML `estimator.localization`). Its `registration` is not
  /// read from the file: the daemon takes estimator.loop_closure's verification settings.
  estimator::LocalizationConfig localization;
  MapFilesConfig map;
  StateConfig state;
  ipc::IpcConfig ipc;
  LoggingConfig logging;
  RecordConfig record;
  RealtimeConfig realtime;
  ControlConfig control;

  /// Every violated rule, keys prefixed by section ("lidar.max_range_m").
  ConfigIssues Validate() const;
};

/// True when `level` is one of spdlog's level names listed in LoggingConfig.
bool IsLogLevelName(const std::string& level);

}  // namespace swlio::daemon

#pragma once
/// @file
/// Live mode: the simulated streams in (N×) real time, LiDAR packets as UDP datagrams to
/// 127.0.0.1 and IMU bytes on a pseudo-terminal, each sent at its simulated receive time.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "live/sim_faults.h"
#include "scenarios/sim_setup.h"

namespace swlio::sim {

struct LiveOptions {
  uint16_t msop_port = 6699;
  uint16_t difop_port = 7788;
  double speed = 1.0;             ///< 2.0 = twice real time
  std::string pty_link;           ///< if set, a symlink to the pty's slave device
  std::filesystem::path out_dir;  ///< groundtruth.tum and manifest.yaml (host times) go here
  /// Wait between the preparation (the IMU samples; a repeated route's first lap, minutes for
  /// loop943) and streaming; "sim: streaming in N s" on stderr marks its start.
  double start_delay_s = 0.0;
  /// Cast every LiDAR packet of the drive during the preparation (about 1 MB per second of
  /// driving) instead of while streaming. Ray casting on the fly keeps up at a few times real
  /// time on an idle core; on a loaded machine (or under a sanitizer) it falls behind, and then
  /// every sample goes out late: the receiver sees sensor clocks running slower than the
  /// `speed` it was told, which no real sensor does (a TSan run of the daemon's live test
  /// streamed at 0.22× while the daemon expected 0.5×, and diverged). A repeated route is
  /// always cast ahead (its first lap).
  bool precast = false;
  /// If set, receives for every IMU sample (in SimulateImu's order) the CLOCK_MONOTONIC time
  /// its frame went into the pty (0: not written), for latency measurements.
  std::vector<int64_t>* imu_write_ns = nullptr;
  LiveFaults faults;  ///< none by default
  /// If set, called (on RunLive's thread) with LiveStats::start_ns as soon as it is fixed, before
  /// the first sample goes out: for a test that must act at a simulation time, however long the
  /// preparation took.
  std::function<void(int64_t start_ns)> on_start;
};

struct LiveStats {
  uint64_t udp_sent = 0;
  uint64_t udp_errors = 0;
  /// Sends later than this (ms) against their schedule are counted in `late_sends`.
  static constexpr double kLateMs = 10.0;
  uint64_t imu_bytes = 0;  ///< written to the pty
  /// Lost: more than a real adapter's buffer held unread (serial_backlog.h). Bytes are never
  /// reordered; those that wait for room are `imu_bytes_delayed`.
  uint64_t imu_bytes_dropped = 0;
  uint64_t imu_bytes_delayed = 0;
  uint64_t imu_backlog_max_bytes = 0;    ///< the most bytes waiting for the reader at once
  double imu_backlog_max_wait_ms = 0.0;  ///< the longest a frame waited for room in the pty
  double max_lateness_ms = 0.0;          ///< how late the worst send was against its schedule
  double lateness_p50_ms = 0.0;          ///< ... the median send
  double lateness_p99_ms = 0.0;
  uint64_t late_sends = 0;  ///< sends (datagrams, IMU bursts) more than kLateMs late
  /// Host time (CLOCK_MONOTONIC) of simulation time 0: a sample due at simulation time t is
  /// sent at start_ns + t / speed.
  int64_t start_ns = 0;
  /// Where the simulator itself fell behind (a starved machine): a span of simulation time whose
  /// sends were all more than kStallMs late, and the worst of them. The first kMaxLateSpans.
  struct LateSpan {
    double from_s = 0.0, to_s = 0.0, worst_ms = 0.0;
  };
  static constexpr double kStallMs = 100.0;
  static constexpr size_t kMaxLateSpans = 10000;
  std::vector<LateSpan> late_spans;
  /// The worst lateness of the sends due in simulation time [from_s, to_s] that were more than
  /// kStallMs late; 0 if none was.
  double WorstLatenessMs(double from_s, double to_s) const;
  FaultCounts faults;  ///< what LiveOptions::faults injected
};

/// Runs until the route ends or `stop` becomes true. Destinations are always 127.0.0.1.
/// Prints the pty slave path to stdout as "pty: /dev/pts/N". Returns false with `error` on a
/// set-up failure.
bool RunLive(const SimSetup& setup,
             const LiveOptions& options,
             const volatile bool* stop,
             LiveStats* stats,
             std::string* error);

}  // namespace swlio::sim

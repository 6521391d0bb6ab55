#pragma once
/// @file
/// `swliod --record DIR`: the raw bytes of every sensor with their host receive times, in the
/// layout the recording reader (swlio-run, swlio-replay) and the simulator share:
///
/// - lidar.pcap: every LiDAR datagram (MSOP and DIFOP) as received; record time = kernel
///   receive time (CLOCK_MONOTONIC ns); UDP destination port = the configured port.
/// - imu.xbus: every byte read from the serial port, in order.
/// - imu.rx.csv: `byte_offset,bytes,t_rx_ns`, one row per read(2).
/// - can.log (with `can.enabled`): every CAN frame in candump format (`(s.us) can0 123#…`).
/// - manifest.yaml: what the daemon was configured with (extrinsic, LiDAR model and ports,
///   serial baud, time base, the published stamps' clock and realtime − monotonic at start).
/// - health.csv: the daemon's health once a second (blackbox/health_row.h); log.txt: its log
///   lines; odometry.tum: the estimator's state at every sweep's end (TUM, IMU frame, daemon
///   time, as swlio-replay --out writes it); config.yaml: the effective configuration.
/// - clock_offsets.csv: `t_monotonic_ns,realtime_minus_monotonic_ns`, a row at the start, one
///   within 50 ms of every change of the offset by over kClockOffsetRowNs (a wall-clock step, or
///   an NTP slew every 0.1 ms) and one at the end if it changed: CLOCK_REALTIME of a host time t
///   is t + the offset of the last row at or before t (within 0.1 ms, except in the ≤ 50 ms
///   between a step and its row). Relates the recording to data stamped in ROS time. Its times
///   are CLOCK_MONOTONIC; the other files' are on the daemon's time base (the same on a robot,
///   time_scale 1). Older recordings have no such file; no reader needs it.
///
/// Receive times are written on the daemon's time base (host time; stretched by --time-scale,
/// time_scale.h, so a simulator recording at N× replays with consistent physics).
/// The rx threads push copies into the recorder's own SPSC queues (drops counted, never
/// blocking them); the recorder thread writes the files and flushes every second.
///
/// As the black box (`record.ring`, docs/blackbox.md) the same folders are the ring's
/// segments (ring_segments.h), rotated every `segment_s` and bounded by `ring_minutes` and
/// `max_disk_mb`; incident events turn spans of them into incidents (incident_store.h).
/// A failed write (a full disk, a read-only or vanished directory) stops the recording for
/// good: inputs are then taken and counted as discarded, so the sensors' threads never wait.

#include <Eigen/Geometry>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/daemon/blackbox/incident_store.h"
#include "swlio/daemon/blackbox/log_tap.h"
#include "swlio/daemon/blackbox/ring_segments.h"
#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/recording/recording_files.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/drivers/can_reader.h"

namespace swlio::daemon {

struct RecorderCounters {
  uint64_t lidar_packets = 0;
  uint64_t serial_bytes = 0;
  bool ring = false;        ///< the black box (else one folder, --record)
  bool stopped = false;     ///< a write failed: nothing more is recorded
  std::string error;        ///< why it stopped
  uint64_t discarded = 0;   ///< inputs taken after it stopped, not written
  uint64_t segments = 0;    ///< closed segments in the ring
  uint64_t ring_bytes = 0;  ///< theirs and the open one's
  uint64_t segments_deleted = 0;
  double ring_span_s = 0.0;  ///< from the oldest segment's start to now
  IncidentCounters incidents;
};

/// What a recording of `config` (not owned; must outlive the recorder) is opened with: its
/// printed configuration, this build's version, and the configuration's LiDAR ports (give the
/// bound ones in `config` when it asked for port 0).
RecordingSetup MakeRecordingSetup(const DaemonConfig& config,
                                  const Eigen::Isometry3d& T_imu_lidar,
                                  const TimeScale& time);

/// A clock_offsets.csv row is written when the offset moved by more than this since the last.
inline constexpr int64_t kClockOffsetRowNs = 100'000;

class Recorder {
 public:
  /// Records into `dir` (created). `T_imu_lidar` goes into the manifest. The ports written
  /// into lidar.pcap are the configuration's (give the bound ones when it asked for port 0).
  /// `stamps`: the published stamps' clock (not owned; outlives this), whose clocks give
  /// clock_offsets.csv; null: the host's clocks.
  static std::unique_ptr<Recorder> Create(const std::filesystem::path& dir,
                                          const DaemonConfig& config,
                                          const Eigen::Isometry3d& T_imu_lidar,
                                          const TimeScale& time,
                                          std::string* error,
                                          const StampClock* stamps = nullptr);
  /// The black box under `setup.config->record.directory` (ring/, incidents/). An earlier
  /// run's segments become an incident `unclean_stop` when that run did not stop cleanly, and
  /// are deleted otherwise. Incidents carry `setup.version`.
  static std::unique_ptr<Recorder> CreateRing(const RecordingSetup& setup,
                                              std::string* error,
                                              const StampClock* stamps = nullptr);
  ~Recorder();

  SpscQueue<LidarPacket>& lidar_queue() { return lidar_; }
  SpscQueue<SerialChunk>& serial_queue() { return serial_; }
  SpscQueue<drivers::CanRxFrame>& can_queue() { return can_; }
  SpscQueue<State>& odometry_queue() { return odometry_; }
  std::vector<QueueCounters> QueueCountersList() const {
    return {lidar_.Counters(), serial_.Counters(), can_.Counters(), odometry_.Counters()};
  }
  /// Any thread: one health.csv row (health_row.h), written within a second.
  void AddHealthRow(std::string row);
  /// Any thread: an incident event (ignored unless the black box records).
  void AddEvent(IncidentEvent event);
  /// Log lines go to log.txt from `tap` (LogTap::Attach()).
  void TapLog(std::shared_ptr<LogTap> tap) { log_tap_ = std::move(tap); }
  /// The black box's incidents (null for --record): IncidentStore::Run needs a thread.
  IncidentStore* incidents() { return store_.get(); }

  /// Writes until `stop` is set, then drains the queues and closes the recording (the black
  /// box: its last segment, open incidents, and the mark of a clean stop).
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  RecorderCounters counters() const;

 private:
  Recorder(const RecordingSetup& setup, const StampClock* stamps);
  bool OpenFolder(const std::filesystem::path& dir, std::string* error);
  bool Drain();
  void WritePacket(const LidarPacket& p);
  /// A clock_offsets.csv row when the offset moved (at most every 10 ms).
  void RecordClockOffset(int64_t now_ns);
  /// Every second: health rows, events, log lines, flush.
  void Housekeep();
  /// After every drain: rotation, and the ring's bounds as soon as its bytes exceed them (by
  /// span every second).
  void BoundRing(int64_t now_ns);
  /// The ring's bounds from record.ring_minutes and record.max_disk_mb.
  RingBounds Bounds() const;
  void TakeSideInputs();
  void Rotate(int64_t t_ns);
  void CloseSegment(int64_t t_ns);
  void StopOnFailure();
  void Finish();

  // In clang-tidy's padding order (the queues are cache-line aligned).
  SpscQueue<LidarPacket> lidar_{"record_lidar", "lidar_rx", "recorder", 8192};
  SpscQueue<SerialChunk> serial_{"record_serial", "imu_rx", "recorder", 4096};
  SpscQueue<drivers::CanRxFrame> can_{"record_can", "can_rx", "recorder", 4096};
  SpscQueue<State> odometry_{"record_odometry", "optimizer", "recorder", 1024};
  std::shared_ptr<const DaemonConfig> owned_config_;  ///< Create's copy (setup_ points at it)
  RecordingSetup setup_;
  ClockSources clocks_;
  std::unique_ptr<RecordingFiles> files_;  ///< null once stopped
  std::unique_ptr<RingSegments> ring_;
  std::unique_ptr<IncidentStore> store_;
  std::shared_ptr<LogTap> log_tap_;
  std::filesystem::path ring_dir_;
  mutable std::mutex side_mutex_;  ///< health rows, events, the status strings
  std::vector<std::string> health_rows_;
  std::vector<IncidentEvent> events_;
  std::string stop_error_;
  std::atomic<uint64_t> lidar_packets_{0}, serial_bytes_{0}, discarded_{0}, ring_bytes_{0};
  std::atomic<bool> stopped_{false};
  int64_t segment_start_ns_ = 0;  ///< daemon time
  int64_t next_offset_check_ns_ = 0;
  int64_t next_trim_ns_ = 0;
  int64_t last_offset_row_ns_ = 0;  ///< the offset of the last row
};

/// The file in ring/ that says the last run stopped cleanly (its segments are no incident).
inline constexpr const char* kCleanStopMark = "clean-stop";
inline constexpr std::string_view kCleanStopText = "swliod stopped cleanly\n";
inline constexpr uint64_t kCleanStopMarkBytes = kCleanStopText.size();

}  // namespace swlio::daemon

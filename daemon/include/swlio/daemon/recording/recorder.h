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

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/drivers/can_reader.h"
#include "swlio/drivers/pcap_file.h"

namespace swlio::daemon {

struct RecorderCounters {
  uint64_t lidar_packets = 0;
  uint64_t serial_bytes = 0;
  uint64_t write_errors = 0;
};

/// A clock_offsets.csv row is written when the offset moved by more than this since the last.
inline constexpr int64_t kClockOffsetRowNs = 100'000;

class Recorder {
 public:
  /// Creates `dir` and its files. `T_imu_lidar` goes into the manifest. The ports written
  /// into lidar.pcap are the configuration's (give the bound ones when it asked for port 0).
  /// `stamps`: the published stamps' clock (not owned; outlives this), whose clocks give
  /// clock_offsets.csv; null: the host's clocks.
  static std::unique_ptr<Recorder> Create(const std::filesystem::path& dir,
                                          const DaemonConfig& config,
                                          const Eigen::Isometry3d& T_imu_lidar,
                                          const TimeScale& time,
                                          std::string* error,
                                          const StampClock* stamps = nullptr);
  ~Recorder();

  SpscQueue<LidarPacket>& lidar_queue() { return lidar_; }
  SpscQueue<SerialChunk>& serial_queue() { return serial_; }
  SpscQueue<drivers::CanRxFrame>& can_queue() { return can_; }
  std::vector<QueueCounters> QueueCountersList() const {
    return {lidar_.Counters(), serial_.Counters(), can_.Counters()};
  }
  /// Writes until `stop` is set, then drains the queues and flushes.
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  RecorderCounters counters() const;

 private:
  Recorder(const DaemonConfig& config, const TimeScale& time);
  bool Drain();
  void WritePacket(const LidarPacket& p);
  /// A clock_offsets.csv row when the offset moved (at most every 10 ms).
  void RecordClockOffset(int64_t now_ns);
  void WriteClockOffset(const ClockOffsetSample& s);
  void Flush();

  // In clang-tidy's padding order (the queues are cache-line aligned).
  SpscQueue<LidarPacket> lidar_{"record_lidar", "lidar_rx", "recorder", 8192};
  SpscQueue<SerialChunk> serial_{"record_serial", "imu_rx", "recorder", 4096};
  SpscQueue<drivers::CanRxFrame> can_{"record_can", "can_rx", "recorder", 4096};
  std::unique_ptr<drivers::PcapWriter> pcap_;
  uint64_t offset_ = 0;
  std::atomic<uint64_t> lidar_packets_{0}, serial_bytes_{0}, write_errors_{0};
  TimeScale time_;  ///< receive times are written on the daemon's time base
  std::string can_interface_;
  std::ofstream can_log_;
  std::ofstream xbus_;
  std::ofstream rx_csv_;
  std::ofstream offsets_csv_;
  ClockSources clocks_;
  int64_t next_offset_check_ns_ = 0;
  int64_t last_offset_row_ns_ = 0;  ///< the offset of the last row (Create writes the first)
  uint16_t msop_port_;              ///< written as the UDP ports of MSOP records
  uint16_t difop_port_;             ///< and of DIFOP records
};

}  // namespace swlio::daemon

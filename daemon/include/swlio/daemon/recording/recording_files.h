#pragma once
/// @file
/// One recording folder's open files, in the layout recorder.h describes, written by the
/// recorder thread only. Every write counts its bytes; the first failure (a full disk, a
/// vanished directory) is kept in error() and nothing more is written to any file after it.

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <string>

#include "swlio/core/types.h"
#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/drivers/can_reader.h"
#include "swlio/drivers/pcap_file.h"

namespace swlio::daemon {

/// What every folder of one daemon run is opened with.
struct RecordingSetup {
  const DaemonConfig* config = nullptr;  ///< not owned; outlives the files
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  TimeScale time;
  std::string config_text;  ///< the effective configuration (PrintConfig), as config.yaml
  std::string version;      ///< this build's (version.h), as the manifest's swlio_version
  uint16_t msop_port = 0;   ///< written as the UDP ports of MSOP records
  uint16_t difop_port = 0;  ///< and of DIFOP records
};

class RecordingFiles {
 public:
  /// Creates `dir` and its files, and writes manifest.yaml, config.yaml and the first row of
  /// clock_offsets.csv (`start`).
  static std::unique_ptr<RecordingFiles> Open(const std::filesystem::path& dir,
                                              const RecordingSetup& setup,
                                              const ClockOffsetSample& start,
                                              std::string* error);
  ~RecordingFiles();
  RecordingFiles(const RecordingFiles&) = delete;
  RecordingFiles& operator=(const RecordingFiles&) = delete;

  /// `t_ns` on the daemon's time base.
  void Packet(int64_t t_ns, bool difop, std::span<const uint8_t> payload);
  void Serial(int64_t t_ns, std::span<const uint8_t> bytes);
  void Can(int64_t t_ns, const drivers::CanRxFrame& frame);
  void ClockOffset(const ClockOffsetSample& s);
  void HealthRow(const std::string& row);  ///< one health.csv row, no newline
  void LogLine(const std::string& line);   ///< one log.txt line, no newline
  void Odometry(const State& state);       ///< one odometry.tum line
  /// Writes buffered data out; false once anything failed.
  bool Flush();
  /// Flushes and closes every file; false once anything failed.
  bool Close();

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  uint64_t bytes() const { return bytes_; }  ///< written so far (pcap: records and frames)
  const std::filesystem::path& dir() const { return dir_; }
  uint64_t lidar_packets() const { return lidar_packets_; }
  uint64_t serial_bytes() const { return serial_offset_; }

 private:
  RecordingFiles() = default;
  /// Keeps the first failure of `what` (with errno's text) and stops writing.
  void Fail(const std::string& what);
  bool Check(std::ofstream& out, const char* name);

  std::filesystem::path dir_;
  std::unique_ptr<drivers::PcapWriter> pcap_;
  std::ofstream xbus_, rx_csv_, offsets_csv_, can_log_, health_csv_, log_txt_, odometry_;
  std::string can_interface_;
  std::string error_;
  uint64_t bytes_ = 0;
  uint64_t serial_offset_ = 0;
  uint64_t lidar_packets_ = 0;
  uint16_t msop_port_ = 0;
  uint16_t difop_port_ = 0;
};

}  // namespace swlio::daemon

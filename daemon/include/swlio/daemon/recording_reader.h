#pragma once
/// @file
/// Reads a recording folder (the simulator's or the daemon recorder's: lidar.pcap, imu.xbus,
/// imu.rx.csv) through the same decoders, scan assembler and clock models as the live daemon,
/// and returns IMU samples and scans on the host clock in processing order: every IMU sample up
/// to a scan's last firing comes before that scan.
///
/// Clock mapping is causal (each time is mapped with the model as it stood when the data
/// arrived), as it would be live. Fixed latencies: an RS16 packet's header time is its first
/// firing, so the packet span (≈ 1.32 ms) is removed; an Xbus frame's transmission time at the
/// configured baud is removed. Unknown network/USB latency beyond that remains as a bias.

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/daemon/time_scale.h"
#include "swlio/drivers/clock_model.h"
#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/lidar_config.h"

namespace swlio::daemon {

struct RecordingEvent {
  enum class Kind { kImu, kScan } kind = Kind::kImu;
  ImuSample imu;
  Scan scan;  ///< host times; points' dt_ns from t_start_ns
};

struct RecordingStats {
  uint64_t imu_samples = 0;
  uint64_t imu_checksum_errors = 0;
  uint64_t imu_skipped_bytes = 0;
  uint64_t lidar_packets = 0;
  uint64_t scans = 0;
  uint64_t partial_scans = 0;
  uint64_t missing_packets = 0;
  drivers::ClockModelStats imu_clock;
  drivers::ClockModelStats lidar_clock;
};

class RecordingReader {
 public:
  /// Opens `dir`; reads the IMU stream at once (small) and the LiDAR pcap lazily.
  static std::unique_ptr<RecordingReader> Open(const std::filesystem::path& dir,
                                               const drivers::LidarConfig& lidar,
                                               const drivers::ImuConfig& imu,
                                               std::string* error);
  ~RecordingReader();
  RecordingReader(const RecordingReader&) = delete;
  RecordingReader& operator=(const RecordingReader&) = delete;

  /// The next event; false at the end of both streams.
  bool Next(RecordingEvent* event);

  const RecordingStats& stats() const { return stats_; }

 private:
  struct Lidar;
  RecordingReader() = default;
  bool ReadImu(const std::filesystem::path& dir, const drivers::ImuConfig& imu, std::string* error);

  std::vector<ImuSample> imu_;
  size_t imu_next_ = 0;
  std::unique_ptr<Lidar> lidar_;
  bool have_scan_ = false;
  Scan pending_scan_;
  RecordingStats stats_;
};

/// T_imu_lidar as the recording's manifest.yaml states it (its `translation_m: [x, y, z]` and
/// `quaternion_xyzw: [x, y, z, w]` lines); none when either is missing. A recording describes
/// its own rig, so callers let it win over a configuration file.
std::optional<Eigen::Isometry3d> ManifestExtrinsic(const std::filesystem::path& dir);

/// `lidar` with the UDP ports the recording's manifest.yaml names (its `msop_port:` and
/// `difop_port:` lines, as the simulator and swliod --record write them), so a recording made
/// on any ports replays without a matching configuration.
/// The time base the recording's receive times are on (its `time_scale:` and `time_origin_ns:`
/// lines, written by swliod --record --time-scale); the identity when absent.
TimeScale ManifestTimeScale(const std::filesystem::path& dir);

drivers::LidarConfig WithManifestPorts(const std::filesystem::path& dir,
                                       drivers::LidarConfig lidar);

}  // namespace swlio::daemon

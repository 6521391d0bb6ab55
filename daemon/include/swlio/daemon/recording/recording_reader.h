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
///
/// Optional streams, only when the caller asks (RecordingReadOptions):
/// - GNSS: the GnssPvtData items (u-blox NAV-PVT) of the MTData2 messages in imu.xbus, stamped
///   with the host time the clock model gives that message's IMU sample. Fixes without a 3-D or
///   2-D fix (fixType < 2 or 5, gnssFixOK clear) or with impossible values are counted and left
///   out. The simulator puts a fix in the message of its own epoch; a real receiver's output
///   latency (the item arriving in a later message) would remain as a bias.
/// - Wheel odometry: can.log (candump log format, drivers/candump_log.h, as swliod --record and
///   the simulator write it) through drivers::WheelOdomDecoder, stamped with the frame's
///   receive time. Those times are on the same time base as lidar.pcap and imu.rx.csv (the
///   recorder writes all three through one TimeScale::ToDaemon), so they are used as they are.
/// Both are merged by time with the IMU samples: every event up to a scan's last firing comes
/// before that scan, and events of the three streams come in nondecreasing time.

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swlio/core/geodetic.h"
#include "swlio/core/types.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/recording/sensor_input.h"
#include "swlio/drivers/can_config.h"
#include "swlio/drivers/clock_model.h"
#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/lidar_config.h"

namespace swlio::daemon {

/// Which optional streams to return besides IMU samples and scans (none by default).
struct RecordingReadOptions {
  bool gnss = false;  ///< kGnss events from the GnssPvtData items in imu.xbus
  /// kWheel events from can.log, decoded with this layout (it must pass ValidateLayout();
  /// `enabled` and `interface` are not looked at). A missing can.log is not an error.
  std::optional<drivers::CanConfig> wheel;
};

class RecordingReader : public SensorInput {
 public:
  /// Opens `dir`; reads the IMU stream at once (small) and the LiDAR pcap lazily. Returns IMU
  /// samples and scans only. Refuses a folder whose manifest is missing or of another
  /// format_version (ManifestVersionProblem).
  static std::unique_ptr<RecordingReader> Open(const std::filesystem::path& dir,
                                               const drivers::LidarConfig& lidar,
                                               const drivers::ImuConfig& imu,
                                               std::string* error);
  /// As above, plus the optional streams `options` asks for (also read at once). Fails when
  /// `options.wheel` is not a valid layout.
  static std::unique_ptr<RecordingReader> Open(const std::filesystem::path& dir,
                                               const drivers::LidarConfig& lidar,
                                               const drivers::ImuConfig& imu,
                                               const RecordingReadOptions& options,
                                               std::string* error);
  ~RecordingReader() override;
  RecordingReader(const RecordingReader&) = delete;
  RecordingReader& operator=(const RecordingReader&) = delete;

  /// The next event; false at the end of both streams.
  bool Next(RecordingEvent* event) override;

  const RecordingStats& stats() const override { return stats_; }

 private:
  struct Lidar;
  RecordingReader() = default;
  bool ReadImu(const std::filesystem::path& dir,
               const drivers::ImuConfig& imu,
               bool gnss,
               std::string* error);
  bool ReadWheel(const std::filesystem::path& dir,
                 const drivers::CanConfig& can,
                 std::string* error);
  /// The optional stream (GNSS or wheel) whose next event comes first, if any is due by `limit_ns`
  /// and not after the next IMU sample.
  bool NextOptional(int64_t limit_ns, RecordingEvent* event);

  std::vector<ImuSample> imu_;
  size_t imu_next_ = 0;
  std::vector<GnssFix> gnss_;
  size_t gnss_next_ = 0;
  std::vector<WheelOdometry> wheel_;
  size_t wheel_next_ = 0;
  std::unique_ptr<Lidar> lidar_;
  bool have_scan_ = false;
  Scan pending_scan_;
  RecordingStats stats_;
};

/// Why the recording in `dir` cannot be read ("" when it can): its manifest.yaml must state
/// `format_version:` drivers::kRecordingFormatVersion (recording_format.h). A version-1
/// recording (LiDAR frame of the RoboSense manual, before issue 32) is refused with what to do:
/// re-simulate it, or for a swliod recording the same extrinsic in the new frame. Open() refuses
/// such a folder with this message.
std::string ManifestVersionProblem(const std::filesystem::path& dir);

/// T_imu_lidar as the recording's manifest.yaml states it (its `translation_m: [x, y, z]` and
/// `quaternion_xyzw: [x, y, z, w]` lines); none when either is missing. A recording describes
/// its own rig, so callers let it win over a configuration file.
std::optional<Eigen::Isometry3d> ManifestExtrinsic(const std::filesystem::path& dir);

/// The time base the recording's receive times are on (its `time_scale:` and `time_origin_ns:`
/// lines, written by swliod --record --time-scale); the identity when absent.
TimeScale ManifestTimeScale(const std::filesystem::path& dir);

/// `lidar` with the UDP ports the recording's manifest.yaml names (its `msop_port:` and
/// `difop_port:` lines, as the simulator and swliod --record write them), so a recording made
/// on any ports replays without a matching configuration.
drivers::LidarConfig WithManifestPorts(const std::filesystem::path& dir,
                                       drivers::LidarConfig lidar);

/// T_imu_base, the chassis base frame (x forward, z up, origin midway between the wheels) in the
/// IMU frame, from the manifest's `wheel:` block (`T_imu_base_translation_m: [x, y, z]`,
/// `T_imu_base_quaternion_xyzw: [x, y, z, w]`, as the simulator writes it); none when absent.
std::optional<Eigen::Isometry3d> ManifestWheelExtrinsic(const std::filesystem::path& dir);

/// The CAN layout of the manifest's `wheel:` block (`can_frame_id`, `can_dlc`,
/// `can_left_byte_offset`, `can_right_byte_offset`, `can_scale_mps_per_lsb`, `track_width_m`:
/// two int16 Intel signed rim speeds in m/s, the simulator's layout); none when incomplete.
std::optional<drivers::CanConfig> ManifestWheelCan(const std::filesystem::path& dir);

/// The GNSS set-up of a recording's manifest (`gnss:` block).
struct ManifestGnss {
  Geodetic origin;  ///< of the local ENU frame the simulator's world frame is
  Eigen::Vector3d antenna_imu_m = Eigen::Vector3d::Zero();  ///< lever arm, IMU frame
  double rate_hz = 0.0;                                     ///< 0 when not stated
  double sigma_h_m = 0.0;  ///< the simulator's error model (σ per horizontal axis); 0: unknown
  double sigma_v_m = 0.0;  ///< σ up; 0: unknown
};

/// The `gnss:` block's origin (`origin_lat_deg`, `origin_lon_deg`, `origin_height_m`) and lever
/// arm (`antenna_imu_m: [x, y, z]`), with `rate_hz`, `sigma_h_m`, `sigma_v_m` when present;
/// none when the origin or the lever arm is missing.
std::optional<ManifestGnss> ManifestGnssSetup(const std::filesystem::path& dir);

}  // namespace swlio::daemon

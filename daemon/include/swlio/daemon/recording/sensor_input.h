#pragma once
/// @file
/// What swlio-run and swlio-replay read: IMU samples, sweeps and the optional GNSS fixes and
/// wheel samples on one host clock, in processing order (every IMU sample up to a sweep's last
/// firing before that sweep), from either a recording folder (recording_reader.h) or a ROS bag
/// (bag_input.h). OpenSensorInput() decides which from the path.

#include <cstdint>
#include <memory>
#include <string>

#include "swlio/core/types.h"
#include "swlio/drivers/clock_model.h"

namespace swlio::daemon {

struct RecordingEvent {
  enum class Kind { kImu, kScan, kGnss, kWheel } kind = Kind::kImu;
  ImuSample imu;
  Scan scan;            ///< host times; points' dt_ns from t_start_ns
  GnssFix gnss;         ///< kGnss (when asked for)
  WheelOdometry wheel;  ///< kWheel (when asked for)

  /// The event's time: the sample's, or the sweep's start.
  int64_t t_ns() const;
};

/// What an input delivered and dropped (fields that do not apply to an input stay zero).
struct RecordingStats {
  uint64_t imu_samples = 0;
  uint64_t imu_checksum_errors = 0;
  uint64_t imu_skipped_bytes = 0;
  uint64_t imu_dropped = 0;  ///< samples without acceleration or rate, or not finite
  uint64_t lidar_packets = 0;
  uint64_t scans = 0;
  uint64_t partial_scans = 0;
  uint64_t missing_packets = 0;
  drivers::ClockModelStats imu_clock;
  drivers::ClockModelStats lidar_clock;
  uint64_t gnss_fixes = 0;            ///< kGnss events
  uint64_t gnss_rejected = 0;         ///< fixes without a usable position, accuracy or time
  uint64_t wheel_samples = 0;         ///< kWheel events
  uint64_t wheel_frames_dropped = 0;  ///< unreadable lines, unusable frames, unpaired or late
  uint64_t wheel_log_missing = 0;     ///< 1 when wheel odometry was asked for and no can.log
};

class SensorInput {
 public:
  virtual ~SensorInput() = default;
  /// The next event; false at the end of every stream.
  virtual bool Next(RecordingEvent* event) = 0;
  virtual const RecordingStats& stats() const = 0;
  /// Lines the user should read after the run (bad messages skipped, …); empty by default.
  virtual std::string Report() const { return {}; }
};

}  // namespace swlio::daemon

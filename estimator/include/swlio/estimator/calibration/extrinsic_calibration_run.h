#pragma once
/// @file
/// Online use of the batch extrinsic calibration (extrinsic_calibrator.h): LiDAR-only odometry
/// runs beside the window on the same sweeps and samples; once its poses span
/// `seconds`, the batch is tried, and again every `retry_s` (on at most the latest 2 ×
/// `seconds`) while the motion has not determined the rotation (no turns yet). The window then
/// restarts on the result (WindowEstimator::ApplyCalibration) with this odometry's map, which
/// does not depend on the extrinsic. Memory is bounded by 2 × `seconds` of poses and samples.
/// A batch over 300 sweeps takes about 0.1–0.3 s, once per try. Pure library.

#include <deque>
#include <optional>

#include "swlio/core/types.h"
#include "swlio/estimator/calibration/extrinsic_calibrator.h"
#include "swlio/estimator/registration/lidar_odometry.h"

namespace swlio::estimator {

class ExtrinsicCalibrationRun {
 public:
  /// `odometry.T_imu_lidar` is the guess.
  ExtrinsicCalibrationRun(const LidarOdometryConfig& odometry, double seconds, double retry_s);

  void AddImu(const ImuSample& sample);
  void AddScan(const Scan& scan);

  /// Runs the batch when due; the result when it was ok (then nothing more is collected).
  std::optional<ExtrinsicCalibration> TryCalibrate();

  /// The odometry's newest LiDAR pose (its world w0) and its maps (w0), for the restart.
  const StampedLidarPose* newest_pose() const { return poses_.empty() ? nullptr : &poses_.back(); }
  const LidarOdometry& odometry() const { return odometry_; }
  int attempts() const { return attempts_; }
  const std::string& last_message() const { return last_message_; }

 private:
  void DropOld();

  LidarOdometryConfig config_;
  LidarOdometry odometry_;
  int64_t window_ns_, retry_ns_;
  int64_t next_try_ns_ = 0;
  std::deque<StampedLidarPose> poses_;
  std::deque<ImuSample> imu_;
  int attempts_ = 0;
  std::string last_message_;
};

}  // namespace swlio::estimator

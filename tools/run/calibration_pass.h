#pragma once
// swlio-run --calibrate-extrinsic: a first pass over the start of the recording with LiDAR-only
// odometry (its map does not depend on the extrinsic), then the batch calibration
// (swlio/estimator/extrinsic_calibrator.h) of its poses against the IMU.

#include <filesystem>
#include <string>

#include "swlio/daemon/daemon_config.h"
#include "swlio/estimator/extrinsic_calibrator.h"
#include "swlio/estimator/lidar_odometry.h"

namespace swlio::run {

/// Runs LiDAR-only odometry with `odometry.T_imu_lidar` as the guess over [start_s, start_s +
/// seconds] of the recording and calibrates. `error` is set when the recording cannot be read.
estimator::ExtrinsicCalibration CalibrationPass(const std::filesystem::path& dir,
                                                const daemon::DaemonConfig& daemon_config,
                                                const estimator::LidarOdometryConfig& odometry,
                                                double start_s,
                                                double seconds,
                                                std::string* error);

}  // namespace swlio::run

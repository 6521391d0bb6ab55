#include "calibration_pass.h"

#include <vector>

#include "swlio/daemon/recording_reader.h"

namespace swlio::run {

estimator::ExtrinsicCalibration CalibrationPass(const std::filesystem::path& dir,
                                                const daemon::DaemonConfig& daemon_config,
                                                const estimator::LidarOdometryConfig& odometry,
                                                double start_s,
                                                double seconds,
                                                std::string* error) {
  auto reader = daemon::RecordingReader::Open(dir, daemon_config.lidar, daemon_config.imu, error);
  if (!reader) return {};
  estimator::LidarOdometry lidar_only(odometry);
  std::vector<estimator::StampedLidarPose> poses;
  std::vector<ImuSample> imu;
  daemon::RecordingEvent e;
  int64_t start_ns = -1, end_ns = 0;
  while (reader->Next(&e)) {
    const bool is_imu = e.kind == daemon::RecordingEvent::Kind::kImu;
    const int64_t t_ns = is_imu ? e.imu.t_ns : e.scan.t_start_ns;
    if (start_ns < 0) {
      start_ns = t_ns + static_cast<int64_t>(start_s * 1e9);
      end_ns = start_ns + static_cast<int64_t>(seconds * 1e9);
    }
    if (t_ns < start_ns) continue;
    if (is_imu) {
      imu.push_back(e.imu);
      lidar_only.AddImu(e.imu);
      if (t_ns >= end_ns) break;  // one sample past the last sweep
      continue;
    }
    if (t_ns >= end_ns) continue;
    const estimator::OdometryResult r = lidar_only.AddScan(e.scan);
    if (r.status != estimator::OdometryStatus::kTracking) continue;
    // The pose LiDAR-only odometry settled on (match.T_world_lidar is unset on the first sweep).
    poses.push_back({r.state.t_ns, r.state.T_world_imu * odometry.T_imu_lidar});
  }
  // The last sweeps may end after the last sample read: keep the poses the IMU spans.
  while (!poses.empty() && !imu.empty() && poses.back().t_ns > imu.back().t_ns) poses.pop_back();
  return estimator::CalibrateExtrinsic(odometry.estimator, poses, imu, odometry.T_imu_lidar);
}

}  // namespace swlio::run

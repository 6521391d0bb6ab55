#pragma once
/// @file
/// Sweeps and IMU samples (host clock, each stream in time order) → estimator results, in
/// either mode. The one sync rule both the daemon's optimizer thread and swlio-run / replay
/// use: the tightly coupled window pre-integrates the IMU up to a sweep's end, so a sweep is
/// processed once an IMU sample past its end has arrived — at once when one already has (live,
/// the IMU usually runs ahead of the sweep's last packet), else with that sample (serial bursts
/// and stalls deliver samples late; otherwise the factor would extrapolate held rates).
/// LiDAR-only mode takes sweeps as they come. Single-threaded; no clock is read here.

#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/core/types.h"
#include "swlio/estimator/registration/lidar_odometry.h"
#include "swlio/estimator/window/window_estimator.h"

namespace swlio::daemon {

struct DaemonConfig;

enum class EstimatorMode : uint8_t { kTightlyCoupled, kLidarOnly };

/// The estimator configs built from the daemon's configuration and the extrinsic in use.
struct EstimatorSetup {
  EstimatorMode mode = EstimatorMode::kTightlyCoupled;
  estimator::LidarOdometryConfig odometry;
  estimator::WindowEstimatorConfig window;
};
/// "tightly-coupled" or "lidar-only" (EstimatorConfig::mode).
EstimatorMode ModeFromConfig(const DaemonConfig& config);

/// `T_imu_lidar` replaces the configuration's extrinsic (e.g. a recording's manifest).
EstimatorSetup MakeEstimatorSetup(const DaemonConfig& config,
                                  const Eigen::Isometry3d& T_imu_lidar,
                                  EstimatorMode mode);

class EstimatorRunner {
 public:
  /// Called for every processed sweep, in order, with the estimator's result (in LiDAR-only
  /// mode only `odometry` is filled).
  using Sink = std::function<void(const Scan& scan, const estimator::WindowResult& result)>;

  EstimatorRunner(const EstimatorSetup& setup, estimator::NowNsFn now_ns, Sink sink);
  ~EstimatorRunner();
  EstimatorRunner(const EstimatorRunner&) = delete;
  EstimatorRunner& operator=(const EstimatorRunner&) = delete;

  void AddImu(const ImuSample& sample);
  /// Chassis wheel odometry (tightly coupled mode with `wheel.enabled`; ignored otherwise).
  void AddWheel(const WheelOdometry& sample);
  /// Takes the sweep (moved from); processed now or once the IMU covers its end and one sample
  /// more.
  void AddScan(Scan&& scan);

  /// Re-initializes the tightly coupled window (WindowEstimator::Reset); false in LiDAR-only
  /// mode, which has no such seam.
  bool Reset();

  /// Sweeps waiting for IMU coverage.
  size_t waiting() const { return waiting_.size(); }
  /// Sweeps dropped because more than `kMaxWaiting` waited (the IMU stopped or is late).
  size_t dropped_waiting() const { return dropped_waiting_; }
  EstimatorMode mode() const { return mode_; }
  /// Points in the estimator's local maps (planes and edges), in either mode.
  size_t map_points() const;
  /// The window (tightly coupled mode), else nullptr.
  const estimator::WindowEstimator* window() const { return window_.get(); }

  /// At most this many sweeps wait for the IMU (2 s at 10 Hz; ~11 MB of points). Beyond it
  /// the waiting sweeps are thinned evenly (ThinWaiting): a serial backlog of seconds that
  /// arrives late but whole then leaves the IMU short gaps to bridge, not one long one.
  static constexpr size_t kMaxWaiting = 20;

 private:
  void Process(const Scan& scan);
  /// Processes the waiting sweeps whose end the second newest IMU sample has passed.
  void ProcessCovered();
  /// Drops the waiting sweep (neither the oldest, which follows the last processed state, nor
  /// the newest) whose neighbours are closest in time: the largest gap grows least.
  void ThinWaiting();

  EstimatorMode mode_;
  std::unique_ptr<estimator::LidarOdometry> odometry_;
  std::unique_ptr<estimator::WindowEstimator> window_;
  Sink sink_;
  std::deque<Scan> waiting_;
  /// The two newest IMU samples' times on the window's time base (the lowest time until they
  /// have come). A sweep is processed once the older one has passed its end: the sample holding
  /// the end and the one after it have come (the cut step's line,
  /// estimator/imu/preintegration.h); 2.5 ms later at 400 Hz.
  int64_t newest_imu_t_ns_ = std::numeric_limits<int64_t>::min();
  int64_t second_newest_imu_t_ns_ = std::numeric_limits<int64_t>::min();
  size_t dropped_waiting_ = 0;
};

}  // namespace swlio::daemon

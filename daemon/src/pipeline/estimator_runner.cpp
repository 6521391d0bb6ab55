#include "swlio/daemon/pipeline/estimator_runner.h"

#include <utility>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {

EstimatorMode ModeFromConfig(const DaemonConfig& config) {
  return config.estimator.mode == "lidar-only" ? EstimatorMode::kLidarOnly
                                               : EstimatorMode::kTightlyCoupled;
}

EstimatorSetup MakeEstimatorSetup(const DaemonConfig& config,
                                  const Eigen::Isometry3d& T_imu_lidar,
                                  EstimatorMode mode) {
  EstimatorSetup s;
  s.mode = mode;
  s.odometry = estimator::MakeOdometryConfig(config.estimator, T_imu_lidar);
  s.window = config.window;
  s.window.odometry = s.odometry;
  return s;
}

EstimatorRunner::EstimatorRunner(const EstimatorSetup& setup, estimator::NowNsFn now_ns, Sink sink)
    : mode_(setup.mode), sink_(std::move(sink)) {
  if (mode_ == EstimatorMode::kTightlyCoupled) {
    window_ = std::make_unique<estimator::WindowEstimator>(setup.window, now_ns);
  } else {
    odometry_ = std::make_unique<estimator::LidarOdometry>(setup.odometry, now_ns);
  }
}

EstimatorRunner::~EstimatorRunner() = default;

void EstimatorRunner::AddWheel(const WheelOdometry& sample) {
  if (window_) window_->AddWheel(sample);
}

bool EstimatorRunner::Reset() {
  if (!window_) return false;
  window_->Reset();
  return true;
}

void EstimatorRunner::AddImu(const ImuSample& sample) {
  if (odometry_) {
    odometry_->AddImu(sample);
    return;
  }
  window_->AddImu(sample);
  // Coverage on the window's time base: the sample measured the motion of its stamp − offset.
  second_newest_imu_t_ns_ = newest_imu_t_ns_;
  newest_imu_t_ns_ = sample.t_ns - window_->imu_time_offset_ns();
  ProcessCovered();
}

void EstimatorRunner::ProcessCovered() {
  while (!waiting_.empty() && waiting_.front().t_end_ns < second_newest_imu_t_ns_) {
    Process(waiting_.front());
    waiting_.pop_front();
  }
}

void EstimatorRunner::AddScan(Scan&& scan) {
  if (odometry_) {
    Process(scan);
    return;
  }
  waiting_.push_back(std::move(scan));
  while (waiting_.size() > kMaxWaiting) ThinWaiting();
  ProcessCovered();
}

void EstimatorRunner::ThinWaiting() {
  if (waiting_.size() < 3) return;
  size_t drop = 1;
  int64_t best_span_ns = waiting_[2].t_end_ns - waiting_[0].t_end_ns;
  for (size_t i = 2; i + 1 < waiting_.size(); ++i) {
    const int64_t span_ns = waiting_[i + 1].t_end_ns - waiting_[i - 1].t_end_ns;
    if (span_ns < best_span_ns) {
      best_span_ns = span_ns;
      drop = i;
    }
  }
  waiting_.erase(waiting_.begin() + static_cast<std::ptrdiff_t>(drop));
  ++dropped_waiting_;
}

void EstimatorRunner::Process(const Scan& scan) {
  estimator::WindowResult result;
  if (window_) {
    result = window_->AddScan(scan);
  } else {
    result.odometry = odometry_->AddScan(scan);
  }
  if (sink_) sink_(scan, result);
}

size_t EstimatorRunner::map_points() const {
  if (window_) return window_->map_points();
  return odometry_->plane_map().size() + odometry_->edge_map().size();
}

}  // namespace swlio::daemon

#include "swlio/daemon/pipeline/optimizer_thread.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

#include "swlio/daemon/runtime/event_log.h"

namespace swlio::daemon {

OptimizerThread::OptimizerThread(const drivers::LidarConfig& lidar,
                                 const EstimatorSetup& setup,
                                 const OptimizerQueues& queues,
                                 const TimeScale& time,
                                 int64_t max_sweep_lag_ns)
    : time_(time),
      shedding_(max_sweep_lag_ns),
      q_(queues),
      runner_(setup,
              &ThreadCpuNowNs,
              [this](const Scan& scan, const estimator::WindowResult& r) { OnResult(scan, r); }),
      lidar_(lidar) {}

void OptimizerThread::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    q_.wake->Wait(20'000);  // a LiDAR packet or an IMU sample, whichever comes first
    ServeResets();
    // IMU first: a sweep is processed once a sample past its end has arrived (wheel odometry
    // before it, so a sweep's wheel samples are in by then).
    DrainWheel();
    DrainImu();
    DrainLidar();
    Publish();
  }
  // Stopping: the rx threads and the propagator have stopped; finish what they queued.
  DrainWheel();
  DrainImu();
  DrainLidar();
  Publish();
}

bool OptimizerThread::RequestReset(std::shared_ptr<PendingCommand> command) {
  return resets_.Push(std::move(command));
}

void OptimizerThread::ServeResets() {
  std::shared_ptr<PendingCommand> command;
  while (resets_.Pop(&command)) {
    if (command->cancelled()) continue;
    if (!runner_.Reset()) {
      command->Finish({control::ReplyStatus::kRefused,
                       "reset re-initializes the tightly coupled window; estimator.mode is "
                       "lidar-only",
                       ""});
      continue;
    }
    // The propagator drops the state it extrapolates, as after a divergence.
    SweepEstimate e;
    e.reset = true;
    e.status = estimator::OdometryStatus::kInitializing;
    e.tracking = TrackingState::kInitializing;
    q_.states_out->Push(e);
    tracking_ = TrackingState::kInitializing;
    ++reinitializations_;  // the estimator's count (Reset), in the status before the reply
    ++operator_resets_;
    recovering_ = false;
    failed_in_a_row_ = 0;
    Publish();
    spdlog::warn(
        "estimator: reset by the operator: re-initializing (static or moving start) at the last "
        "good pose, with a new local map");
    command->Finish({control::ReplyStatus::kOk,
                     "the estimator re-initializes at the last good pose (state initializing "
                     "until a static or moving start succeeds)",
                     ""});
  }
}

void OptimizerThread::DrainImu() {
  ImuSample sample;
  while (q_.imu_in->Pop(&sample)) {
    runner_.AddImu(sample);
    newest_imu_t_ns_ = sample.t_ns;
  }
}

void OptimizerThread::DrainWheel() {
  if (q_.wheel_in == nullptr) return;
  WheelOdometry sample;
  while (q_.wheel_in->Pop(&sample)) {
    sample.t_ns = time_.ToDaemon(sample.t_ns);
    runner_.AddWheel(sample);
  }
}

void OptimizerThread::DrainLidar() {
  LidarPacket packet;
  while (q_.lidar_in->Pop(&packet)) {
    lidar_.Add(std::span(packet.bytes).first(packet.size), time_.ToDaemon(packet.t_rx_ns));
    while (lidar_.Pop(&sweep_)) {
      if (!shedding_.Take(time_.ToDaemon(MonotonicNowNs()) - sweep_.host_rx_last_ns)) continue;
      rx_by_end_.emplace_back(sweep_.scan.t_end_ns, time_.ToHost(sweep_.host_rx_last_ns));
      if (rx_by_end_.size() > EstimatorRunner::kMaxWaiting + 2) rx_by_end_.pop_front();
      // The IMU that arrived meanwhile first: while a backlog of packets drains (the
      // estimator fell behind for a while), sweeps must not pile up waiting for samples that
      // sit in the queue; more than kMaxWaiting would be dropped (a soak at 10x did that).
      DrainImu();
      runner_.AddScan(std::move(sweep_.scan));
    }
  }
}

int64_t OptimizerThread::LastRxOf(int64_t t_end_ns) const {
  for (const auto& [end, rx] : rx_by_end_) {
    if (end == t_end_ns) return rx;
  }
  return 0;
}

TrackingState OptimizerThread::Classify(const estimator::OdometryResult& r) {
  using estimator::OdometryStatus;
  if (r.status == OdometryStatus::kInitializing)
    return recovering_ ? TrackingState::kLost : TrackingState::kInitializing;
  if (r.status == OdometryStatus::kSkipped) return tracking_;
  recovering_ = false;
  failed_in_a_row_ = r.status == OdometryStatus::kMatchFailed ? failed_in_a_row_ + 1 : 0;
  if (failed_in_a_row_ >= kLostAfterSweeps) return TrackingState::kLost;
  if (failed_in_a_row_ > 0 || r.match.degenerate_directions > 0) return TrackingState::kDegraded;
  return TrackingState::kTracking;
}

void OptimizerThread::OnResult(const Scan& scan, const estimator::WindowResult& result) {
  const estimator::OdometryResult& r = result.odometry;
  reinitializations_ = result.reinitializations;  // the estimator's count
  wheel_factors_ = result.wheel_factors;
  wheel_rejected_ = result.wheel_rejected;
  standing_still_ = result.standstill;
  standstill_sweeps_ = result.standstill_frames;
  time_offset_ = result.time_offset;
  dynamic_removed_ = result.dynamic_removed_total;
  if (result.diverged != estimator::DivergenceReason::kNone) {
    recovering_ = true;
    last_divergence_ = result.diverged;
    const double t_s = static_cast<double>(time_.ToHost(scan.t_end_ns)) * 1e-9;
    LogEvent(spdlog::level::warn, "divergence",
             fmt::format("estimator: state diverged ({}) at the sweep ending {:.3f} s; "
                         "re-initializing (static or moving start) at the last good pose, with a "
                         "new local map",
                         estimator::ToString(result.diverged), t_s),
             {{"REASON", estimator::ToString(result.diverged)},
              {"SWEEP_END_S", fmt::format("{:.3f}", t_s)},
              {"REINITIALIZATIONS", std::to_string(result.reinitializations)}});
  }
  tracking_ = Classify(r);
  last_sweep_t_ns_ = scan.t_end_ns;
  degenerate_ = r.match.degenerate_directions;
  last_ms_ = r.times.total_ms;
  max_ms_ = std::max(max_ms_, last_ms_);
  ++processed_;
  SweepEstimate e;
  e.state = r.state;
  e.covariance = result.covariance;
  e.status = r.status;
  e.tracking = tracking_;
  e.degenerate_directions = degenerate_;
  e.update_ms = last_ms_;
  e.scan_last_rx_ns = LastRxOf(scan.t_end_ns);
  e.keyframe = r.keyframe;
  if (const estimator::WindowEstimator* w = runner_.window(); w != nullptr) {
    e.T_imu_lidar = w->T_imu_lidar();
    e.has_extrinsic = true;
    e.imu_time_offset_ns = w->imu_time_offset_ns();
  }
  e.reset = result.diverged != estimator::DivergenceReason::kNone;
  q_.states_out->Push(e);
  q_.odometry_out->Push(e);
  if (record_ != nullptr && (r.status == estimator::OdometryStatus::kTracking ||
                             r.status == estimator::OdometryStatus::kMatchFailed)) {
    State host = r.state;  // as swlio-replay --out writes it
    host.t_ns = time_.ToHost(host.t_ns);
    record_->Push(host);
  }
  if (q_.keyframes_out != nullptr && result.keyframe != nullptr) {
    q_.keyframes_out->Push(KeyframePtr(result.keyframe));
  }
  const bool tracked = r.status == estimator::OdometryStatus::kTracking;
  const estimator::WindowEstimator* window = runner_.window();
  if (sweeps_ != nullptr && tracked && window != nullptr) {  // after the pose went out
    sweeps_->Publish(window->deskewed(), r.state.T_world_imu * window->T_imu_lidar(),
                     time_.ToHost(scan.t_end_ns));
  }
  Publish();  // per sweep: a backlog drained in one go still shows each state in the health
}

void OptimizerThread::Publish() {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  snapshot_.lidar = lidar_.counters();
  snapshot_.lidar_clock = lidar_.clock();
  snapshot_.processed = processed_;
  snapshot_.dropped_waiting = runner_.dropped_waiting();
  snapshot_.skipped_behind = shedding_.skipped();
  snapshot_.map_points = runner_.map_points();
  snapshot_.tracking = tracking_;
  const int64_t imu_only_ns = newest_imu_t_ns_ - last_sweep_t_ns_;
  const bool carried =
      tracking_ == TrackingState::kTracking || tracking_ == TrackingState::kDegraded;
  snapshot_.imu_only_s = 0.0;
  if (carried && last_sweep_t_ns_ > 0 && imu_only_ns > kImuOnlyDegradedNs) {
    snapshot_.tracking = TrackingState::kDegraded;
    snapshot_.imu_only_s =
        static_cast<double>(time_.ToHost(newest_imu_t_ns_) - time_.ToHost(last_sweep_t_ns_)) * 1e-9;
  }
  snapshot_.last_sweep_end_host_ns = last_sweep_t_ns_ > 0 ? time_.ToHost(last_sweep_t_ns_) : 0;
  snapshot_.degenerate_directions = degenerate_;
  snapshot_.last_update_ms = last_ms_;
  snapshot_.max_update_ms = max_ms_;
  snapshot_.reinitializations = reinitializations_;
  snapshot_.operator_resets = operator_resets_;
  snapshot_.wheel_factors = wheel_factors_;
  snapshot_.wheel_rejected = wheel_rejected_;
  snapshot_.standing_still = standing_still_;
  snapshot_.standstill_sweeps = standstill_sweeps_;
  snapshot_.time_offset = time_offset_;
  snapshot_.dynamic_removed = dynamic_removed_;
  snapshot_.recovering = recovering_;
  snapshot_.last_divergence = estimator::ToString(last_divergence_);
}

OptimizerCounters OptimizerThread::counters() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return snapshot_;
}

}  // namespace swlio::daemon

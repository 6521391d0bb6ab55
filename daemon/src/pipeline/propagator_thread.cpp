#include "swlio/daemon/pipeline/propagator_thread.h"

#include "swlio/daemon/output/message_conversion.h"

namespace swlio::daemon {

ipc::Covariance6 GrownPoseCovariance(const estimator::StateCovariance& covariance, double dt_s) {
  if (!covariance.valid) return {};
  estimator::StateCovariance grown = covariance;
  const auto& P = covariance.P;
  grown.P.block<3, 3>(0, 0) +=
      P.block<3, 3>(6, 6) * dt_s * dt_s + (P.block<3, 3>(0, 6) + P.block<3, 3>(6, 0)) * dt_s;
  return PoseCovariance(grown);
}

PropagatorThread::PropagatorThread(int64_t imu_baud,
                                   const estimator::ImuRatePropagatorConfig& config,
                                   const PropagatorQueues& queues,
                                   const TimeScale& time)
    : q_(queues),
      time_(time),
      decoder_([this](const drivers::xsens::MtData2Sample& sample, int64_t t_rx_ns) {
        OnSample(sample, t_rx_ns);
      }),
      stage_(imu_baud),
      propagator_(config) {}

void PropagatorThread::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  SerialChunk chunk;
  auto decode = [this, &chunk] {
    decoder_.Process({chunk.bytes.data(), chunk.size}, chunk.t_rx_ns, chunk.epoch);
    SendHeldPose();
  };
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    ApplyStates();
    if (!q_.serial_in->WaitPop(&chunk, 50'000)) {
      Publish();
      continue;
    }
    decode();
    if (since_publish_ >= 100) Publish();
  }
  // Stopping: the rx threads have stopped; finish what they queued.
  while (q_.serial_in->Pop(&chunk)) decode();
  ApplyStates();
  Publish();
}

void PropagatorThread::OnSample(const drivers::xsens::MtData2Sample& sample, int64_t t_rx_ns) {
  ++since_publish_;
  ApplyStates();  // a chunk may hold several samples: a new state applies before the next
  Handle(ToImuRaw(sample, t_rx_ns, decoder_.last_frame_bytes()));
}

void PropagatorThread::ApplyStates() {
  SweepEstimate e;
  while (q_.states_in->Pop(&e)) {
    if (e.reset) {  // the estimator restarted: no output from its diverged state
      propagator_.Clear();
      held_pose_.reset();
      covariance_ = {};
      continue;
    }
    if (e.status == estimator::OdometryStatus::kInitializing ||
        e.status == estimator::OdometryStatus::kSkipped) {
      continue;  // no state
    }
    imu_time_offset_ns_ = e.imu_time_offset_ns;
    if (propagator_.SetState(e.state)) {
      covariance_ = e.covariance;
      ++states_;
    }
  }
}

void PropagatorThread::Handle(const ImuRaw& raw) {
  ImuRaw scaled = raw;
  scaled.t_rx_ns = time_.ToDaemon(raw.t_rx_ns);
  const std::optional<ImuSample> sample = stage_.Map(scaled);
  if (!sample) return;
  read_lag_.Add(raw.t_rx_ns - time_.ToHost(sample->t_ns));
  last_sample_t_ns_ = sample->t_ns;
  q_.imu_out->Push(*sample);
  if (raw.has_gnss_pvt && q_.gnss_out != nullptr) {
    const std::optional<GnssFix> fix = drivers::xsens::ToGnssFix(raw.gnss_pvt, sample->t_ns);
    if (fix) q_.gnss_out->Push(*fix);
    (fix ? gnss_fixes_ : gnss_unusable_)++;
  }
  // On the estimator's time base: the sample measured the motion of its stamp − the offset.
  ImuSample measured = *sample;
  measured.t_ns -= imu_time_offset_ns_;
  const std::optional<estimator::ImuRateOutput> out = propagator_.Add(measured);
  if (!out) return;
  ImuRatePose pose;
  pose.state = out->state;
  pose.gyro_imu_radps = out->gyro_imu_radps;
  pose.since_optimized_ns = out->since_optimized_ns;
  pose.rx_ns = raw.t_rx_ns;
  pose.pose_covariance =
      GrownPoseCovariance(covariance_, static_cast<double>(out->since_optimized_ns) * 1e-9);
  Offer(pose, raw.t_rx_ns - time_.ToHost(sample->t_ns) > kStalePoseNs);
}

void PropagatorThread::Offer(const ImuRatePose& pose, bool stale) {
  if (held_pose_) ++poses_coalesced_;  // a newer pose of the same read replaces it
  held_pose_.reset();
  if (stale) {
    held_pose_ = pose;
    return;
  }
  q_.poses_out->Push(pose);
  ++poses_;
}

void PropagatorThread::SendHeldPose() {
  if (!held_pose_) return;
  q_.poses_out->Push(*held_pose_);
  held_pose_.reset();
  ++poses_;
}

void PropagatorThread::Publish() {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  since_publish_ = 0;
  const drivers::xsens::XsensStreamStats& d = decoder_.stats();
  a_decoded_.store(d.samples, kRelaxed);
  a_checksum_errors_.store(d.framer.checksum_errors, kRelaxed);
  a_skipped_bytes_.store(d.framer.skipped_bytes, kRelaxed);
  a_missing_packets_.store(d.missing_packets, kRelaxed);
  a_counter_gaps_.store(d.counter_gaps, kRelaxed);
  a_restarts_.store(d.restarts, kRelaxed);
  const ImuStageCounters& c = stage_.counters();
  a_samples_.store(c.samples, kRelaxed);
  a_dropped_.store(c.no_sample_time + c.incomplete + c.out_of_order, kRelaxed);
  a_invalid_.store(c.incomplete, kRelaxed);
  a_poses_.store(poses_, kRelaxed);
  a_poses_coalesced_.store(poses_coalesced_, kRelaxed);
  a_states_.store(states_, kRelaxed);
  a_jumps_.store(stage_.clock().jumps, kRelaxed);
  a_gnss_fixes_.store(gnss_fixes_, kRelaxed);
  a_gnss_unusable_.store(gnss_unusable_, kRelaxed);
  a_last_sample_t_ns_.store(last_sample_t_ns_, kRelaxed);
  a_offset_ns_.store(stage_.clock().offset_ns, kRelaxed);
  a_drift_ppm_.store(stage_.clock().drift_ppm, kRelaxed);
}

PropagatorCounters PropagatorThread::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  PropagatorCounters c;
  c.decode.samples = a_decoded_.load(kRelaxed);
  c.decode.checksum_errors = a_checksum_errors_.load(kRelaxed);
  c.decode.skipped_bytes = a_skipped_bytes_.load(kRelaxed);
  c.decode.missing_packets = a_missing_packets_.load(kRelaxed);
  c.decode.counter_gaps = a_counter_gaps_.load(kRelaxed);
  c.decode.restarts = a_restarts_.load(kRelaxed);
  c.samples = a_samples_.load(kRelaxed);
  c.dropped = a_dropped_.load(kRelaxed);
  c.invalid = a_invalid_.load(kRelaxed);
  c.poses = a_poses_.load(kRelaxed);
  c.poses_coalesced = a_poses_coalesced_.load(kRelaxed);
  c.states = a_states_.load(kRelaxed);
  c.clock_jumps = a_jumps_.load(kRelaxed);
  c.clock_offset_ns = a_offset_ns_.load(kRelaxed);
  c.clock_drift_ppm = a_drift_ppm_.load(kRelaxed);
  c.last_sample_t_ns = a_last_sample_t_ns_.load(kRelaxed);
  c.gnss_fixes = a_gnss_fixes_.load(kRelaxed);
  c.gnss_unusable = a_gnss_unusable_.load(kRelaxed);
  c.read_lag = read_lag_.Snapshot();
  return c;
}

}  // namespace swlio::daemon

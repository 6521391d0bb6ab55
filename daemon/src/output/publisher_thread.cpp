#include "swlio/daemon/output/publisher_thread.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace swlio::daemon {

PublisherThread::PublisherThread(ipc::Publisher* publisher,
                                 OutputFrames frames,
                                 const PublisherQueues& queues,
                                 const TimeScale& time,
                                 HealthFn health,
                                 int64_t health_period_ns,
                                 size_t path_max_poses,
                                 const estimator::CorrectionSlewConfig& slew)
    : publisher_(publisher),
      frames_(std::move(frames)),
      q_(queues),
      time_(time),
      health_(std::move(health)),
      health_period_ns_(health_period_ns),
      path_max_poses_(std::max<size_t>(path_max_poses, 1)),
      slew_(slew) {
  path_.frame_id = frames_.names.map;
  tf_.transforms.reserve(2);
}

void PublisherThread::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  ImuRatePose pose;
  SweepEstimate estimate;
  UpdateStampClock();
  WriteStaticTf();
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    q_.wake->Wait(20'000);  // a pose or an odometry, whichever comes first
    UpdateStampClock();
    TakeCorrections();
    while (q_.poses_in->Pop(&pose)) WritePose(pose);
    while (q_.odometry_in->Pop(&estimate)) WriteOdometry(estimate);
    Periodic(MonotonicNowNs());
  }
  TakeCorrections();  // stopping: what the others queued last
  while (q_.poses_in->Pop(&pose)) WritePose(pose);
  while (q_.odometry_in->Pop(&estimate)) WriteOdometry(estimate);
}

void PublisherThread::UpdateStampClock() {
  if (stamps_ == nullptr) return;
  const std::optional<WallClockStep> step = stamps_->Update();
  if (!step) return;
  spdlog::warn(
      "wall clock stepped by {:+.6f} s (realtime - monotonic now {:.6f} s; {} step(s) since the "
      "start): {}; the estimator's time is unaffected",
      static_cast<double>(step->step_ns) * 1e-9, static_cast<double>(step->offset_ns) * 1e-9,
      stamps_->counters().steps,
      stamps_->realtime() ? "published stamps (CLOCK_REALTIME) jump with it"
                          : "published stamps stay on CLOCK_MONOTONIC");
}

int64_t PublisherThread::Stamp(int64_t t_daemon_ns) const {
  const int64_t host_ns = time_.ToHost(t_daemon_ns);
  return stamps_ != nullptr ? stamps_->ToStamp(host_ns) : host_ns;
}

void PublisherThread::TakeCorrections() {
  if (q_.corrections_in == nullptr) return;
  MapCorrection c;
  while (q_.corrections_in->Pop(&c)) {
    if (c.jump) {
      slew_.JumpTo(c.T_map_odom);
      holding_ = false;
    } else {
      slew_.SetTarget(c.T_map_odom);
    }
    if (c.path != nullptr) ReplacePath(*c.path);
  }
}

void PublisherThread::ReplacePath(const std::vector<estimator::MapNode>& nodes) {
  keyframes_.clear();
  const size_t first = nodes.size() > path_max_poses_ ? nodes.size() - path_max_poses_ : 0;
  for (size_t i = first; i < nodes.size(); ++i) {
    ipc::PoseStamped p;
    p.t_ns = Stamp(nodes[i].t_ns);
    p.frame_id = frames_.names.map;
    p.pose = ToPose(BasePose(nodes[i].T_map_imu, frames_.T_imu_base));
    keyframes_.push_back(std::move(p));
  }
  path_changed_ = true;
}

const Eigen::Isometry3d& PublisherThread::StepCorrection(int64_t t_ns,
                                                         const Eigen::Isometry3d& T_odom_imu,
                                                         bool send) {
  const Eigen::Isometry3d& C = slew_.Step(t_ns, T_odom_imu);
  if (!stored_correction_ || C.matrix() != stored_T_map_odom_.matrix()) {
    correction_cell_.Store(C);
    stored_T_map_odom_ = C;
    stored_correction_ = true;
  }
  if (!send) return C;
  // Sent whenever the C applied to this pose is not the one sent last, so that every sample
  // holds for the poses up to the next; stamped like this pose even when a sweep's odometry
  // stepped C to a later time (its end may lie up to max_imu_lag_s past the newest pose).
  const bool changed = C.matrix() != sent_T_map_odom_.matrix();
  const bool due = t_ns - sent_map_odom_t_ns_ >= map_odom_period_ns_;
  if (!sent_map_odom_ || changed || due) {
    tf_.transforms.push_back(ToTransform(Stamp(t_ns), frames_.names.map, frames_.names.odom, C));
    sent_T_map_odom_ = C;
    sent_map_odom_t_ns_ = std::max(sent_map_odom_t_ns_, t_ns);
    sent_map_odom_ = true;
  }
  return C;
}

void PublisherThread::Count(bool ok, std::atomic<uint64_t>* counter) {
  (ok ? *counter : failures_).fetch_add(1, std::memory_order_relaxed);
}

namespace {

bool Finite(const ipc::Pose& p) {
  bool finite = true;
  for (const double v : p.position_m) finite = finite && std::isfinite(v);
  for (const double v : p.orientation_xyzw) finite = finite && std::isfinite(v);
  return finite;
}

/// C · T, exactly T while there is no correction.
Eigen::Isometry3d Apply(const Eigen::Isometry3d& C, const Eigen::Isometry3d& T) {
  return C.matrix() == Eigen::Matrix4d::Identity() ? T : C * T;
}

/// `s` moved into the map frame by the correction C.
State InMap(const Eigen::Isometry3d& C, State s) {
  if (C.matrix() == Eigen::Matrix4d::Identity()) return s;
  s.T_world_imu = C * s.T_world_imu;
  s.vel_world = C.linear() * s.vel_world;
  return s;
}

}  // namespace

void PublisherThread::WriteTf() {
  if (tf_.transforms.empty()) return;
  Count(publisher_ == nullptr || publisher_->PublishTf(tf_), &transforms_);
  tf_.transforms.clear();
}

void PublisherThread::WriteStaticTf() {
  const int64_t host_ns = MonotonicNowNs();
  const ipc::TFMessage tf =
      StaticTransforms(stamps_ != nullptr ? stamps_->ToStamp(host_ns) : host_ns, frames_);
  Count(publisher_ == nullptr || publisher_->PublishTfStatic(tf), &transforms_);
}

void PublisherThread::WritePose(const ImuRatePose& pose) {
  last_gyro_imu_radps_ = pose.gyro_imu_radps;
  const Eigen::Isometry3d T_odom_base = BasePose(pose.state.T_world_imu, frames_.T_imu_base);
  if (!Finite(ToPose(T_odom_base))) {  // the planner must never receive one
    non_finite_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  const int64_t stamp = Stamp(pose.state.t_ns);
  tf_.transforms.clear();
  tf_.transforms.push_back(
      ToTransform(stamp, frames_.names.odom, frames_.names.base_link, T_odom_base));
  if (holding_) {
    held_.fetch_add(1, std::memory_order_relaxed);
    WriteTf();
    return;
  }
  const Eigen::Isometry3d& C = StepCorrection(pose.state.t_ns, pose.state.T_world_imu, true);
  ipc::PoseWithCovarianceStamped m;
  m.t_ns = stamp;
  m.frame_id = frames_.names.map;
  m.pose = ToPose(Apply(C, T_odom_base));
  if (!Finite(m.pose)) {
    non_finite_.fetch_add(1, std::memory_order_relaxed);
    WriteTf();
    return;
  }
  m.covariance = BasePoseCovariance(pose.pose_covariance, pose.state.T_world_imu.linear(),
                                    frames_.T_imu_base.translation());
  Count(publisher_ == nullptr || publisher_->PublishPose(m), &poses_);
  pose_latency_.Add(MonotonicNowNs() - pose.rx_ns);
  WriteTf();
}

void PublisherThread::FollowExtrinsic(const SweepEstimate& e) {
  // 0.1 mm / 0.006°: below that a refinement is noise, and /tf_static is latched (each new
  // sample replaces the last for every late joiner).
  if (!e.has_extrinsic) return;
  const Eigen::Isometry3d d = frames_.T_imu_lidar.inverse() * e.T_imu_lidar;
  if (d.translation().norm() < 1e-4 && Eigen::AngleAxisd(d.linear()).angle() < 1e-4) return;
  frames_.T_imu_lidar = e.T_imu_lidar;
  WriteStaticTf();
  static_resends_.fetch_add(1, std::memory_order_relaxed);
}

void PublisherThread::WriteOdometry(const SweepEstimate& e) {
  if (e.status == estimator::OdometryStatus::kInitializing ||
      e.status == estimator::OdometryStatus::kSkipped) {
    return;
  }
  FollowExtrinsic(e);
  const ipc::FrameNames& names = frames_.names;
  ipc::Odometry odom = ToOdometryMessage(e.state, last_gyro_imu_radps_, e.covariance,
                                         frames_.T_imu_base, names.odom, names.base_link);
  if (!Finite(odom.pose)) {
    non_finite_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  odom.t_ns = Stamp(odom.t_ns);
  Count(publisher_ == nullptr || publisher_->PublishOdomOdometry(odom), &odom_odometry_);
  if (holding_) {
    held_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  const Eigen::Isometry3d& C = StepCorrection(e.state.t_ns, e.state.T_world_imu, false);
  ipc::Odometry m = ToOdometryMessage(InMap(C, e.state), last_gyro_imu_radps_, e.covariance,
                                      frames_.T_imu_base, names.map, names.base_link);
  m.t_ns = odom.t_ns;
  if (!Finite(m.pose)) {
    non_finite_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  Count(publisher_ == nullptr || publisher_->PublishOdometry(m), &odometry_);
  if (e.keyframe) {
    ipc::PoseStamped p;
    p.t_ns = m.t_ns;
    p.frame_id = names.map;
    p.pose = m.pose;
    keyframes_.push_back(p);
    if (keyframes_.size() > path_max_poses_) keyframes_.pop_front();
    path_.t_ns = p.t_ns;
    path_changed_ = true;
  }
}

void PublisherThread::Periodic(int64_t now_ns) {
  if (now_ns < next_health_ns_) return;
  next_health_ns_ = now_ns + health_period_ns_;
  if (health_) {
    ipc::DiagnosticArray h = health_(now_ns);  // stamped on the host clock
    if (stamps_ != nullptr) h.t_ns = stamps_->ToStamp(h.t_ns);
    Count(publisher_ == nullptr || publisher_->PublishHealth(h), &health_count_);
  }
  if (path_changed_) {
    path_.poses.assign(keyframes_.begin(), keyframes_.end());
    Count(publisher_ == nullptr || publisher_->PublishPath(path_), &paths_);
    path_changed_ = false;
  }
}

PublisherCounters PublisherThread::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  PublisherCounters c;
  c.poses = poses_.load(kRelaxed);
  c.odometry = odometry_.load(kRelaxed);
  c.health = health_count_.load(kRelaxed);
  c.paths = paths_.load(kRelaxed);
  c.failures = failures_.load(kRelaxed);
  c.non_finite = non_finite_.load(kRelaxed);
  c.held = held_.load(kRelaxed);
  c.odom_odometry = odom_odometry_.load(kRelaxed);
  c.transforms = transforms_.load(kRelaxed);
  c.static_resends = static_resends_.load(kRelaxed);
  c.pose_latency = pose_latency_.Snapshot();
  return c;
}

}  // namespace swlio::daemon

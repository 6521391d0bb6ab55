#include "swlio/daemon/runtime/runtime.h"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <utility>

#include "swlio/core/time.h"
#include "swlio/daemon/blackbox/health_row.h"
#include "swlio/daemon/runtime/event_log.h"
#include "swlio/daemon/runtime/thread_setup.h"
#include "swlio/estimator/map/saved_map.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/publisher.h"
#include "swlio/ipc/subscriber.h"

namespace swlio::daemon {

/// The queues, named by what flows and between which threads (health lists them).
struct Runtime::Queues {
  // 4096 packets ≈ 5 s of RS16 single return (750 packets/s): a slow solve never drops.
  SpscQueue<LidarPacket> lidar{"lidar_packets", "lidar_rx", "optimizer", 4096};
  // The stream's bytes, decoded on the propagator: one chunk per read(2) of 50–500 bytes, at
  // worst one per 400 Hz sample, so 2048 chunks (~2 MB) hold ≥ 5 s (≥ 2.5 s of reads split in
  // two per sample).
  SpscQueue<SerialChunk> imu_serial{"imu_serial", "imu_rx", "propagator", 2048};
  // As many samples as a USB-serial adapter's tty buffer holds (640 KiB, tty_buffer.c; 10,900
  // frames of 60 bytes, 27 s at 400 Hz) and more: a kernel worker that was starved for seconds
  // releases the backlog at once, faster than the optimizer drains it (56 bytes each: 0.9 MB).
  SpscQueue<ImuSample> imu{"imu_samples", "propagator", "optimizer", 16384};
  SpscQueue<SweepEstimate> states{"states", "optimizer", "propagator", 64};
  SpscQueue<SweepEstimate> odometry{"odometry", "optimizer", "publisher", 64};
  // 2.5 s at 400 Hz; a backlog's stale samples give one pose per read (PropagatorThread).
  SpscQueue<ImuRatePose> poses{"poses", "propagator", "publisher", 1024};
  // ~50 s of keyframes at 5/s: a loop solve of tens of ms never drops one.
  SpscQueue<KeyframePtr> keyframes{"keyframes", "optimizer", "loop_closure", 256};
  SpscQueue<MapCorrection> corrections{"corrections", "loop_closure", "publisher", 16};
  // GNSS fixes come at 4 Hz, wheel odometry at ~50 Hz: seconds of slack each.
  SpscQueue<GnssFix> gnss{"gnss_fixes", "propagator", "loop_closure", 64};
  SpscQueue<WheelOdometry> wheel{"wheel_odometry", "can_rx", "optimizer", 512};
  Doorbell optimizer_wake;  // rung by lidar and imu
  Doorbell publisher_wake;  // rung by poses and odometry

  Queues() {
    lidar.RingOnPush(&optimizer_wake);
    imu.RingOnPush(&optimizer_wake);
    poses.RingOnPush(&publisher_wake);
    odometry.RingOnPush(&publisher_wake);
  }

  std::vector<QueueCounters> Counters() const {
    return {lidar.Counters(),     imu_serial.Counters(),  imu.Counters(),
            states.Counters(),    odometry.Counters(),    poses.Counters(),
            keyframes.Counters(), corrections.Counters(), gnss.Counters(),
            wheel.Counters()};
  }
};

Runtime::Runtime(const DaemonConfig& config, const RuntimeOptions& options)
    : config_(config),
      options_(options),
      watchdog_(options.stall_timeout_ns),
      queues_(std::make_unique<Queues>()) {}

Runtime::~Runtime() {
  Stop();
  LogTap::Detach(log_tap_);
  if (can_socket_ >= 0) close(can_socket_);
}

std::unique_ptr<Runtime> Runtime::Create(const DaemonConfig& config,
                                         const RuntimeOptions& options,
                                         std::string* error) {
  std::unique_ptr<Runtime> rt(new Runtime(config, options));
  Queues& q = *rt->queues_;
  rt->lidar_rx_ = LidarRx::Open(config.lidar, &q.lidar, error);
  if (!rt->lidar_rx_) return nullptr;
  if (options.dds) {
    rt->participant_ = ipc::Participant::Create(config.ipc, error);
    if (!rt->participant_) return nullptr;
    rt->publisher_ = ipc::Publisher::Create(*rt->participant_, config.ipc, error);
    if (!rt->publisher_) return nullptr;
  }
  rt->imu_rx_ = std::make_unique<ImuRx>(config.imu, &q.imu_serial);
  if (config.can.enabled) {
    int fd = options.can_fd;
    if (fd < 0) fd = rt->can_socket_ = drivers::OpenCanRawSocket(config.can.interface, error);
    if (fd < 0) return nullptr;
    rt->can_rx_ = CanRx::Create(config.can, fd, error);
    if (!rt->can_rx_) return nullptr;
  }
  const TimeScale time{MonotonicNowNs(), options.time_scale};
  rt->stamp_clock_ = std::make_unique<StampClock>(IsRealtimeStampClock(config.ipc.stamp_clock),
                                                  options.stamp_clocks);
  const Eigen::Isometry3d T_imu_lidar =
      options.T_imu_lidar.value_or(config.estimator.extrinsic_imu_lidar.ToIsometry());
  rt->time_ = time;
  if (!rt->MakeRecorder(T_imu_lidar, time, error)) return nullptr;
  const EstimatorSetup setup = MakeEstimatorSetup(config, T_imu_lidar, ModeFromConfig(config));
  // Loop closure and localization need the window's keyframes (tightly coupled mode);
  // localizing in a saved map replaces loop closure.
  const bool tight = setup.mode == EstimatorMode::kTightlyCoupled;
  if (config.map.localize && !tight) {
    *error = "map.localize needs estimator.mode tightly-coupled";
    return nullptr;
  }
  const bool localize = config.map.localize;
  // The pose graph runs for loop detection, for GNSS, or both.
  const bool gnss = config.loop_closure.gnss.enabled && tight && !localize;
  const bool loops = (config.loop_closure.enabled || gnss) && tight && !localize;
  if (config.loop_closure.gnss.enabled && !gnss)
    spdlog::warn("GNSS: needs estimator.mode tightly-coupled and no localization; off");
  estimator::ImuRatePropagatorConfig propagator;
  propagator.gravity_mps2 = config.estimator.gravity_mps2;
  propagator.rebase_rate_mps = config.estimator.output_rebase_rate_mps;
  propagator.rebase_rate_radps = config.estimator.output_rebase_rate_radps;
  rt->propagator_ = std::make_unique<PropagatorThread>(
      config.imu.baud, propagator,
      PropagatorQueues{&q.imu_serial, &q.states, &q.imu, &q.poses, gnss ? &q.gnss : nullptr}, time);
  const bool wheel = setup.window.wheel.enabled && tight && rt->can_rx_ != nullptr;
  if (wheel) rt->can_rx_->SendTo(&q.wheel);
  if (config.loop_closure.enabled && !tight)
    spdlog::warn("loop closure: needs estimator.mode tightly-coupled; off");
  if (config.loop_closure.enabled && localize)
    spdlog::info("loop closure: off while localizing in a saved map");
  const bool keyframes = loops || localize;
  rt->optimizer_ = std::make_unique<OptimizerThread>(
      config.lidar, setup,
      OptimizerQueues{&q.lidar, &q.imu, &q.states, &q.odometry, &q.optimizer_wake,
                      keyframes ? &q.keyframes : nullptr, wheel ? &q.wheel : nullptr},
      time, SecToNs(config.realtime.max_sweep_lag_s));
  if (rt->recorder_) rt->optimizer_->RecordOdometryTo(&rt->recorder_->odometry_queue());
  if (loops) {
    rt->loop_closure_ = std::make_unique<LoopClosureThread>(
        config.loop_closure,
        LoopClosureQueues{&q.keyframes, &q.corrections, gnss ? &q.gnss : nullptr});
  }
  if (localize && !rt->LoadLocalization(error)) return nullptr;
  OutputFrames frames;
  frames.names = config.ipc.frames;
  frames.T_imu_base = config.window.wheel.T_imu_base.ToIsometry();  // identity unless configured
  frames.T_imu_lidar = T_imu_lidar;
  rt->MakeMapPublisher(frames.names.map);
  if (!rt->ReadPoseHints(frames, error)) return nullptr;
  Runtime* self = rt.get();
  rt->publisher_thread_ = std::make_unique<PublisherThread>(
      rt->publisher_.get(), frames,
      PublisherQueues{&q.poses, &q.odometry, &q.publisher_wake,
                      keyframes ? &q.corrections : nullptr},
      time,
      [self](int64_t) {
        ipc::DiagnosticArray health = self->published_health_.Diagnostics(self->Snapshot());
        std::lock_guard<std::mutex> lock(self->health_mutex_);
        self->last_health_ = health;
        return health;
      },
      1'000'000'000, static_cast<size_t>(config.ipc.path_max_poses),
      estimator::CorrectionSlewConfig{config.loop_closure.output_max_rate_mps,
                                      config.loop_closure.output_max_rate_radps});
  rt->publisher_thread_->StampWith(rt->stamp_clock_.get());
  rt->publisher_thread_->SetMapOdomPeriod(SecToNs(config.ipc.map_odom_period_s));
  if (localize) rt->publisher_thread_->HoldUntilLocalized();
  if (rt->publisher_ && rt->publisher_->PublishesSweeps() && tight) {
    rt->sweep_publisher_ = std::make_unique<SweepPublisher>(rt->publisher_.get(), frames.names.map);
    rt->sweep_publisher_->StampWith(rt->stamp_clock_.get());
    rt->sweep_publisher_->CorrectWith(&rt->publisher_thread_->correction());
    rt->optimizer_->PublishSweepsTo(rt->sweep_publisher_.get());
  }
  rt->OpenControl();
  return rt;
}

bool Runtime::MakeRecorder(const Eigen::Isometry3d& T_imu_lidar,
                           const TimeScale& time,
                           std::string* error) {
  const bool ring = options_.record_dir.empty() && config_.record.ring;
  if (options_.record_dir.empty() && !ring) return true;
  DaemonConfig& recorded = recorded_config_;  // the ports actually bound (tests ask for any)
  recorded = config_;
  recorded.lidar.msop_port = lidar_rx_->msop_port();
  recorded.lidar.difop_port = lidar_rx_->difop_port();
  if (!ring) {
    recorder_ = Recorder::Create(options_.record_dir, recorded, T_imu_lidar, time, error,
                                 stamp_clock_.get());
    if (!recorder_) return false;
  } else {
    std::string why;
    recorder_ = Recorder::CreateRing(MakeRecordingSetup(recorded, T_imu_lidar, time), &why,
                                     stamp_clock_.get());
    if (!recorder_) {
      blackbox_error_ = why;
      spdlog::error("{}; the daemon runs without it", why);
      return true;
    }
    spdlog::info(
        "black box: the last {:.1f} min in {} (at most {} MB); incidents: {:.0f} s before "
        "to {:.0f} s after an event",
        config_.record.ring_minutes, config_.record.directory, config_.record.max_disk_mb,
        config_.record.incident_before_s, config_.record.incident_after_s);
  }
  log_tap_ = LogTap::Attach();
  recorder_->TapLog(log_tap_);
  lidar_rx_->RecordTo(&recorder_->lidar_queue());
  imu_rx_->RecordTo(&recorder_->serial_queue());
  if (can_rx_) can_rx_->RecordTo(&recorder_->can_queue());
  return true;
}

void Runtime::ObserveForRecording(const HealthSnapshot& s,
                                  const std::vector<std::string>& stalled) {
  if (!recorder_) return;
  const int64_t t_ns = time_.ToDaemon(s.t_ns);
  const int64_t realtime_ns = s.t_ns + stamp_clock_->counters().offset_ns;
  recorder_->AddHealthRow(HealthCsvRow(s, t_ns, realtime_ns, ReadProcessUsage()));
  if (!recorder_->incidents()) return;
  for (IncidentEvent& e : incident_detector_.Update(s, t_ns, realtime_ns, stalled)) {
    LogEvent(spdlog::level::warn, "incident", "incident: " + e.reason + ": " + e.detail,
             {{"REASON", e.reason}, {"DETAIL", e.detail}});
    recorder_->AddEvent(std::move(e));
  }
}

bool Runtime::LoadLocalization(std::string* error) {
  std::optional<estimator::SavedMap> map = estimator::LoadMapFile(config_.map.load_path, error);
  if (!map) return false;
  if (map->nodes.empty()) {
    *error = "map file " + config_.map.load_path + ": no nodes to localize in";
    return false;
  }
  spdlog::info("localization: map {} with {} nodes; relocalizing", config_.map.load_path,
               map->nodes.size());
  if (map->file_version == estimator::kSavedMapVersionManualFrame) {
    spdlog::warn(
        "localization: map {} is version 1 (LiDAR frame of the RoboSense manual), "
        "converted to the drivers' frame on reading; save it again to store version 2",
        config_.map.load_path);
  }
  estimator::LocalizationConfig c = config_.localization;
  c.registration = config_.loop_closure;
  localization_ = std::make_unique<LocalizationThread>(
      std::move(*map), c, LoopClosureQueues{&queues_->keyframes, &queues_->corrections});
  return true;
}

bool Runtime::ReadPoseHints(const OutputFrames& frames, std::string* error) {
  if (localization_) localization_->SetBaseFrame(frames.T_imu_base.inverse());
  if (loop_closure_) loop_closure_->SetBaseFrame(frames.T_imu_base.inverse());
  const std::string& topic = config_.ipc.initialpose_topic;
  if (topic.empty() || !participant_) return true;
  if (!localization_ && !loop_closure_) {
    spdlog::warn(
        "ipc.initialpose_topic: pose hints need a map frame (localizing in a saved map, or "
        "loop closure while mapping); /{} is not read",
        topic);
    return true;
  }
  ipc::IpcConfig c = config_.ipc;
  c.pose_topic = topic;
  ipc::SubscriberOptions options;
  options.topics.fill(false);
  options.topics[static_cast<size_t>(ipc::Topic::kPose)] = true;
  options.history_depth = 10;
  hint_reader_ = ipc::Subscriber::Create(*participant_, c, options, error);
  if (!hint_reader_) {
    *error = "ipc.initialpose_topic: " + *error;
    return false;
  }
  if (localization_) localization_->ReadHintsFrom(hint_reader_.get(), frames.names.map);
  if (loop_closure_) loop_closure_->ReadHintsFrom(hint_reader_.get(), frames.names.map);
  spdlog::info("pose hints from /{} (frame {}): {}", topic, frames.names.map,
               localization_ ? "relocalize in the saved map" : "re-anchor the map being built");
  return true;
}

void Runtime::MakeMapPublisher(const std::string& frame_id) {
  const ipc::IpcConfig& c = config_.ipc;
  if (!publisher_ || c.map_publish_period_s <= 0.0 || (!loop_closure_ && !localization_)) return;
  map_publisher_ = std::make_unique<MapPublisher>(
      publisher_.get(), frame_id, static_cast<size_t>(c.map_max_points), c.map_publish_period_s);
  map_publisher_->StampWith(stamp_clock_.get());
  if (loop_closure_) loop_closure_->PublishMapTo(map_publisher_.get());
  if (localization_) localization_->PublishMapTo(map_publisher_.get());
}

void Runtime::SaveMap() {
  if (!loop_closure_ || config_.map.save_path.empty() || map_saved_) return;
  map_saved_ = true;
  std::string error;
  const size_t nodes =
      loop_closure_->SaveMap(config_.map.save_path, config_.map.save_path + ".pcd", &error);
  if (!error.empty()) {
    spdlog::error("map: not saved: {}", error);
  } else {
    spdlog::info("map: {} nodes saved to {} (merged cloud: {}.pcd)", nodes, config_.map.save_path,
                 config_.map.save_path);
  }
}

void Runtime::Spawn(std::vector<std::thread>* group,
                    const char* name,
                    std::function<void(const Watchdog::Handle&)> body) {
  Watchdog::Handle beat = watchdog_.Register(name);
  group->emplace_back([this, name, beat, body = std::move(body)] {
    for (const std::string& problem : SetUpThisThread(name, config_.realtime)) {
      spdlog::warn("realtime: {}", problem);
      sched_failures_.fetch_add(1);
    }
    body(beat);
  });
}

void Runtime::Start() {
  if (control_) {
    Spawn(&control_threads_, "control",
          [this](const Watchdog::Handle& b) { control_->Run(stop_control_, b); });
  }
  auto* rx = &rx_threads_;
  auto* out = &out_threads_;
  Spawn(rx, "lidar_rx", [this](const Watchdog::Handle& b) { lidar_rx_->Run(stop_rx_, b); });
  Spawn(rx, "imu_rx", [this](const Watchdog::Handle& b) { imu_rx_->Run(stop_rx_, b); });
  if (can_rx_) {
    Spawn(rx, "can_rx", [this](const Watchdog::Handle& b) { can_rx_->Run(stop_rx_, b); });
  }
  Spawn(&propagator_threads_, "propagator",
        [this](const Watchdog::Handle& b) { propagator_->Run(stop_propagator_, b); });
  Spawn(&optimizer_threads_, "optimizer",
        [this](const Watchdog::Handle& b) { optimizer_->Run(stop_optimizer_, b); });
  if (loop_closure_) {
    Spawn(&loop_threads_, "loop_closure",
          [this](const Watchdog::Handle& b) { loop_closure_->Run(stop_loop_, b); });
  }
  if (localization_) {
    Spawn(&loop_threads_, "localization",
          [this](const Watchdog::Handle& b) { localization_->Run(stop_loop_, b); });
  }
  Spawn(out, "publisher",
        [this](const Watchdog::Handle& b) { publisher_thread_->Run(stop_out_, b); });
  if (recorder_) {
    Spawn(out, "recorder", [this](const Watchdog::Handle& b) { recorder_->Run(stop_out_, b); });
  }
  if (recorder_ && recorder_->incidents() != nullptr) {
    Spawn(&keeper_threads_, "incidents",
          [this](const Watchdog::Handle& b) { recorder_->incidents()->Run(stop_keeper_, b); });
  }
}

void Runtime::Stop() {
  for (auto [flag, group] :
       {std::pair{&stop_control_, &control_threads_}, std::pair{&stop_rx_, &rx_threads_},
        std::pair{&stop_propagator_, &propagator_threads_},
        std::pair{&stop_optimizer_, &optimizer_threads_}, std::pair{&stop_loop_, &loop_threads_},
        std::pair{&stop_out_, &out_threads_}, std::pair{&stop_keeper_, &keeper_threads_}}) {
    flag->store(true);
    for (std::thread& t : *group) {
      if (t.joinable()) t.join();
    }
    group->clear();
    if (group == &control_threads_) control_.reset();  // closes and removes the socket
    if (group == &loop_threads_) SaveMap();            // the graph is complete and nobody writes it
  }
}

bool Runtime::Ready() const {
  const HealthSnapshot s = Snapshot();
  return s.propagator.samples > 0 && s.optimizer.lidar.sweeps > 0 &&
         s.optimizer.tracking != TrackingState::kInitializing;
}

HealthSnapshot Runtime::Snapshot() const {
  HealthSnapshot s;
  s.t_ns = MonotonicNowNs();
  s.lidar_rx = lidar_rx_->counters();
  s.imu_rx = imu_rx_->counters();
  if (can_rx_) s.can_rx = can_rx_->counters();
  s.can_enabled = can_rx_ != nullptr;
  s.propagator = propagator_->counters();
  s.optimizer = optimizer_->counters();
  s.publisher = publisher_thread_->counters();
  if (loop_closure_) s.loop_closure = loop_closure_->counters();
  if (localization_) s.localization = localization_->counters();
  if (map_publisher_) s.map = map_publisher_->counters();
  if (sweep_publisher_) s.sweeps = sweep_publisher_->counters();
  s.stamp_clock = stamp_clock_->counters();
  s.queues = queues_->Counters();
  if (recorder_) {
    for (const QueueCounters& c : recorder_->QueueCountersList()) s.queues.push_back(c);
    s.recording = true;
    s.recorder = recorder_->counters();
  } else if (!blackbox_error_.empty()) {
    s.recording = true;
    s.recorder.ring = true;
    s.recorder.stopped = true;
    s.recorder.error = blackbox_error_;
  }
  return s;
}

uint16_t Runtime::msop_port() const { return lidar_rx_->msop_port(); }
uint16_t Runtime::difop_port() const { return lidar_rx_->difop_port(); }

}  // namespace swlio::daemon

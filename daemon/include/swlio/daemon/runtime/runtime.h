#pragma once
/// @file
/// The running daemon: the threads of design.md wired by their SPSC queues.
///
///   lidar_rx ──packets──► optimizer ──states──► propagator ◄──serial bytes── imu_rx
///                            ▲  └──odometry──► publisher ◄──poses──┘  │
///                            └───────────── IMU samples ──────────────┘
///
/// With --record, a recorder thread takes copies from both rx threads.
/// Each thread registers with the Watchdog and beats every loop (≤ 100 ms apart when idle).
/// Stop() stops and joins in stages: the control thread (no new commands); then upstream first:
/// the rx threads; the propagator; the optimizer; the publisher and the recorder. Each finishes
/// what is queued for it, so the estimator, the outputs and the recording see everything that was
/// received. No allocation on the rx threads after Create().

#include <Eigen/Geometry>
#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "swlio/daemon/blackbox/incident_detector.h"
#include "swlio/daemon/blackbox/log_tap.h"
#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/control/control_server.h"
#include "swlio/daemon/output/map_publisher.h"
#include "swlio/daemon/output/message_conversion.h"
#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/daemon/pipeline/estimator_runner.h"
#include "swlio/daemon/pipeline/time_scale.h"
#include "swlio/daemon/recording/recorder.h"
#include "swlio/daemon/runtime/health.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/daemon/sensors/can_rx.h"

namespace swlio::ipc {
class Participant;
class Publisher;
class Subscriber;
}  // namespace swlio::ipc

namespace swlio::daemon {

struct RuntimeOptions {
  bool dds = true;  ///< false: run without DDS (publisher thread counts but writes nothing)
  int64_t stall_timeout_ns = 2'000'000'000;  ///< Watchdog: a thread silent this long is stalled
  /// Sensor seconds per host second (time_scale.h): 1 except for a simulator at N× speed.
  double time_scale = 1.0;
  /// Replaces the configuration's extrinsic (e.g. a simulator's or recording's rig).
  std::optional<Eigen::Isometry3d> T_imu_lidar;
  /// Record the raw sensor bytes into this folder (recorder.h); empty: no recording, or the
  /// black box when the configuration's record.ring is on (a folder given here wins).
  std::filesystem::path record_dir;
  /// With `can.enabled`: read CAN frames from this fd instead of opening `can.interface` (tests
  /// use a socketpair; not owned). −1: open the interface.
  int can_fd = -1;
  /// The clocks the published stamps' offset is read from (stamp_clock.h); empty: the host's.
  /// Tests step the wall clock through `realtime`.
  ClockSources stamp_clocks;
};

/// With control.socket, a control thread serves swlioctl (control_server.h); Runtime is its
/// ControlTarget (runtime_control.cpp).
class Runtime : public ControlTarget {
 public:
  /// Opens the UDP sockets and the DDS participant; the serial device is opened (and
  /// re-opened) by the imu_rx thread. Nullptr with `error` filled on failure.
  static std::unique_ptr<Runtime> Create(const DaemonConfig& config,
                                         const RuntimeOptions& options,
                                         std::string* error);
  ~Runtime() override;
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  void Start();
  /// Asks every thread to finish and joins them. Idempotent.
  void Stop();

  /// Sensors stream and the estimator has a state (the READY=1 condition).
  bool Ready() const;
  HealthSnapshot Snapshot() const;
  /// The supervision loop, about once a second: a health.csv row for the recording and, for
  /// the black box, incident events from the health (incident_detector.h), each also logged.
  /// `s`: a Snapshot() just taken; `stalled`: the watchdog's stalled threads.
  void ObserveForRecording(const HealthSnapshot& s, const std::vector<std::string>& stalled);
  const Watchdog& watchdog() const { return watchdog_; }
  /// The daemon's time base (time_scale.h): recordings and incidents are stamped on it.
  const TimeScale& time_scale() const { return time_; }
  uint16_t msop_port() const;
  uint16_t difop_port() const;
  uint64_t sched_failures() const { return sched_failures_.load(); }
  /// The control socket's path; empty when there is none (off, or it could not be created).
  std::string control_socket() const { return control_ ? control_->path() : std::string(); }
  ControlCounters control_counters() const {
    return control_ ? control_->counters() : ControlCounters{};
  }

  // ControlTarget (called on the control thread).
  std::string Status() override;
  std::shared_ptr<PendingCommand> Submit(const control::Request& request,
                                         control::Reply* refusal) override;

 private:
  struct Queues;
  Runtime(const DaemonConfig& config, const RuntimeOptions& options);
  /// Loads map.load_path and makes the localization thread; false with *error.
  bool LoadLocalization(std::string* error);
  /// The map cloud's publisher, handed to the loop-closure or localization thread (when DDS
  /// runs and ipc.map_publish_period_s > 0).
  void MakeMapPublisher(const std::string& frame_id);
  /// With ipc.initialpose_topic while localizing: the DDS reader of operators' pose hints,
  /// handed to the localization thread. False with *error when DDS refuses the reader.
  bool ReadPoseHints(const OutputFrames& frames, std::string* error);
  /// With loop closure and map.save_path: the graph as a saved map (once, at stop).
  void SaveMap();
  /// The control socket (control.socket): a failure is logged and the daemon runs without.
  void OpenControl();
  /// swlioctl mark: an incident event now (answered at once; refused without the black box).
  std::shared_ptr<PendingCommand> Mark(std::shared_ptr<PendingCommand> command,
                                       control::Reply* refusal);
  /// The health message the publisher built last (what `status` reports).
  std::optional<ipc::DiagnosticArray> LastHealth() const;
  /// --record DIR or the black box (record.ring); false with *error only for --record (the
  /// black box's failure is logged and shown in health: the daemon runs without it).
  bool MakeRecorder(const Eigen::Isometry3d& T_imu_lidar,
                    const TimeScale& time,
                    std::string* error);
  void Spawn(std::vector<std::thread>* group,
             const char* name,
             std::function<void(const Watchdog::Handle&)> body);

  DaemonConfig config_;
  DaemonConfig recorded_config_;  ///< config_ with the bound ports: the recording's
  RuntimeOptions options_;
  Watchdog watchdog_;
  std::unique_ptr<Queues> queues_;
  /// The published stamps' clock: sampled by the publisher thread, read by the map publisher,
  /// the recorder and Snapshot.
  std::unique_ptr<StampClock> stamp_clock_;
  std::unique_ptr<ipc::Participant> participant_;
  std::unique_ptr<ipc::Publisher> publisher_;
  std::unique_ptr<ipc::Subscriber> hint_reader_;  ///< ipc.initialpose_topic; localization only
  std::unique_ptr<LidarRx> lidar_rx_;
  std::unique_ptr<ImuRx> imu_rx_;
  std::unique_ptr<CanRx> can_rx_;  ///< only with can.enabled
  int can_socket_ = -1;            ///< the CAN_RAW socket Runtime opened (closed on destruction)
  std::unique_ptr<PropagatorThread> propagator_;
  std::unique_ptr<OptimizerThread> optimizer_;
  std::unique_ptr<LoopClosureThread> loop_closure_;   ///< only with estimator.loop_closure
  std::unique_ptr<LocalizationThread> localization_;  ///< only with map.localize
  /// With DDS, either of the two above and ipc.map_publish_period_s > 0; used by that thread.
  std::unique_ptr<MapPublisher> map_publisher_;
  std::unique_ptr<SweepPublisher> sweep_publisher_;  ///< ipc.sweep_topic; used by the optimizer
  std::unique_ptr<PublisherThread> publisher_thread_;
  std::unique_ptr<Recorder> recorder_;
  std::shared_ptr<LogTap> log_tap_;     ///< the recorder's log.txt source
  std::string blackbox_error_;          ///< why record.ring could not start
  IncidentDetector incident_detector_;  ///< the supervision loop's (ObserveForRecording)
  TimeScale time_;                      ///< the daemon's time base
  HealthReporter published_health_;     ///< used by the publisher thread only
  mutable std::mutex health_mutex_;     ///< guards last_health_
  std::optional<ipc::DiagnosticArray> last_health_;  ///< publisher → control thread
  std::unique_ptr<ControlServer> control_;           ///< null without a control socket
  std::atomic<uint64_t> sched_failures_{0};          ///< realtime settings a thread could not apply
  std::atomic<bool> stop_control_{false};
  std::atomic<bool> stop_rx_{false};
  std::atomic<bool> stop_propagator_{false};
  std::atomic<bool> stop_optimizer_{false};
  std::atomic<bool> stop_loop_{false};
  bool map_saved_ = false;
  std::atomic<bool> stop_out_{false};     ///< publisher, recorder
  std::atomic<bool> stop_keeper_{false};  ///< the incidents' keeper, after the recorder
  std::vector<std::thread> control_threads_;
  std::vector<std::thread> rx_threads_;
  std::vector<std::thread> propagator_threads_;
  std::vector<std::thread> optimizer_threads_;
  std::vector<std::thread> loop_threads_;
  std::vector<std::thread> out_threads_;
  std::vector<std::thread> keeper_threads_;
};

}  // namespace swlio::daemon

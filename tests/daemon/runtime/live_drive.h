#pragma once
// A simulated drive streamed live into a Runtime (UDP to 127.0.0.1, Xbus on a pseudo-terminal),
// with what a field engineer would watch: the health snapshots every 100 ms, and what a
// subscriber receives over DDS (poses, odometry, the published health). For the end-to-end
// daemon tests and the fault-injection tests.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "live/sim_live.h"
#include "scenarios/sim_setup.h"
#include "swlio/daemon/runtime/runtime.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/subscriber.h"
#include "test_data.h"
#include "udp_port.h"

namespace swlio::daemon::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool kSanitized = true;  // several times slower: the optimizer may fall behind
#else
inline constexpr bool kSanitized = false;
#endif

struct LiveDrive {
  std::string scenario = "short";
  uint64_t seed = 11;
  double duration_s = 12.0;
  std::optional<double> stand_start_s;  ///< standing before driving off (the scenario's: 2 s)
  double speed = 1.0;  ///< N× real time (the daemon is told); sanitized builds always 0.5
  sim::LiveFaults faults;
  std::function<void(sim::SimSetup*)> adjust_setup;  ///< e.g. the sensors' clocks
  std::function<void(DaemonConfig*)> adjust_config;
  std::filesystem::path record_dir;  ///< empty: no recording
  ClockSources stamp_clocks;         ///< the published stamps' clocks (empty: the host's)
  /// Called from the simulator's thread with the host time (CLOCK_MONOTONIC) of simulation
  /// time 0 and the speed, once the preparation is over (sim::LiveOptions::on_start).
  std::function<void(int64_t start_ns, double speed)> on_sim_start;
  /// Every test its own DDS domain, or one test's subscriber takes another's samples (the ipc
  /// tests publish edge values such as NaN and DBL_MAX: a CI-like run of ctest -j2 saw them
  /// arrive here). tests/ipc uses 101..138 and 163..164 (DdsSecurity); the daemon tests 140..162,
  /// 165 and 166:
  /// Runtime.* 140, RuntimeFaults.* 141..153 and 156, SwliodCommand 154, Runtime.AWallClockStep…
  /// 157, RuntimeControl.* 159, RuntimeFastDdsTf.* 161, RuntimeInitialPose.* 162,
  /// RuntimeBlackBox.Keeps… 165, RuntimeBlackBox.AFullDisk… 166; not live drives:
  /// MapPublisher 155, PublisherThreadTf 158 and 160. Benchmarks use 200 and up
  /// (bench/daemon_latency.cpp).
  uint32_t dds_domain = 140;
};

struct HealthSample {
  double t_s = 0.0;  ///< simulation time
  HealthSnapshot snapshot;
};

struct LiveDriveResult {
  bool sim_ok = false;
  std::string error;
  sim::LiveStats stats;
  double speed = 1.0;
  std::optional<sim::SimSetup> setup;
  DaemonConfig config;
  TimeScale daemon_time;             ///< the Runtime's time base (recordings' times are on it)
  bool ready = false;                ///< the READY=1 condition held at some point
  std::vector<HealthSample> health;  ///< every 100 ms
  HealthSnapshot final;              ///< after Stop
  std::vector<ipc::Received<ipc::PoseWithCovarianceStamped>> poses;
  size_t odometry = 0;
  std::vector<ipc::Received<ipc::PointCloud2>> sweeps;  ///< ipc.sweep_topic (the reader keeps 1)
  std::vector<ipc::Received<ipc::DiagnosticArray>> published_health;

  /// Simulation time of a host (CLOCK_MONOTONIC) time.
  double SimTime(int64_t host_ns) const {
    return static_cast<double>(host_ns - stats.start_ns) * 1e-9 * speed;
  }
  /// Poses stamped in [from_s, to_s) of simulation time.
  size_t PosesBetween(double from_s, double to_s) const {
    size_t n = 0;
    for (const auto& p : poses) {
      const double t = SimTime(p.msg.t_ns);
      n += t >= from_s && t < to_s ? 1 : 0;
    }
    return n;
  }
  /// The health snapshots whose estimator state came from a sweep that ended in [from_s, to_s)
  /// of simulation time: what the daemon made of those sweeps, however far behind it ran.
  std::vector<const HealthSnapshot*> StatesOfSweepsBetween(double from_s, double to_s) const {
    std::vector<const HealthSnapshot*> out;
    for (const HealthSample& h : health) {
      const int64_t end_ns = h.snapshot.optimizer.last_sweep_end_host_ns;
      const double t = SimTime(end_ns);
      if (end_ns != 0 && t >= from_s && t < to_s) out.push_back(&h.snapshot);
    }
    return out;
  }
  /// The last health snapshot taken before simulation time t_s.
  const HealthSnapshot& HealthAt(double t_s) const {
    const HealthSnapshot* last = &health.front().snapshot;
    for (const HealthSample& h : health) {
      if (h.t_s < t_s) last = &h.snapshot;
    }
    return *last;
  }
  /// Prints the published status of `name` (e.g. "swlio: estimator") at every health message
  /// of the run: the health output a field engineer sees.
  void ShowPublished(const std::string& name) const {
    for (const auto& a : published_health) {
      for (const auto& s : a.msg.status) {
        if (s.name != name) continue;
        std::cout << "[ health ] t " << SimTime(a.msg.t_ns) << " s  " << s.name << ": "
                  << s.message;
        for (const auto& kv : s.values) std::cout << "  " << kv.key << "=" << kv.value;
        std::cout << "\n";
      }
    }
  }
  /// Whether any published status `name` had a message containing `text`.
  /// The newest published health message of status `name` that contains `text`, or nullptr.
  const std::string* LastPublished(const std::string& name, const std::string& text) const {
    const std::string* found = nullptr;
    for (const auto& a : published_health) {
      for (const auto& s : a.msg.status) {
        if (s.name == name && s.message.find(text) != std::string::npos) found = &s.message;
      }
    }
    return found;
  }
  bool PublishedSaid(const std::string& name, const std::string& text) const {
    return LastPublished(name, text) != nullptr;
  }
};

inline DaemonConfig LiveDriveConfig(const std::filesystem::path& dir, uint32_t domain) {
  DaemonConfig config;
  config.lidar.bind_address = "127.0.0.1";
  // Free ports no DDS participant sends to (udp_port.h); told to the simulator.
  config.lidar.msop_port = ::swlio::test::QuietUdpPort();
  config.lidar.difop_port = ::swlio::test::QuietUdpPort();
  config.imu.device = (dir / "imu.pty").string();
  config.imu.configure_on_start = false;
  config.ipc.domain_id = domain;
  // The simulator's time is CLOCK_MONOTONIC (LiveStats::start_ns), and so are SimTime's stamps;
  // stamps in ROS time (the default) are tested by Runtime.AWallClockStepMovesTheStampsOnly.
  config.ipc.stamp_clock = "monotonic";
  config.ipc.dds_config_file =
      (::swlio::test::SourceDir() / "config" / "cyclonedds-loopback.xml").string();
  // No control socket unless a test asks (RuntimeControl.*): the default /run/swlio is the
  // installed daemon's.
  config.control.socket = "";
  return config;
}

/// Runs the drive to its end (sanitized builds at half speed) and stops the Runtime.
inline LiveDriveResult RunLiveDrive(const LiveDrive& drive) {
  LiveDriveResult out;
  out.setup = sim::MakeSimSetup(drive.scenario, drive.seed, drive.duration_s, std::nullopt,
                                drive.stand_start_s);
  if (!out.setup) {
    out.error = "unknown scenario " + drive.scenario;
    return out;
  }
  if (drive.adjust_setup) drive.adjust_setup(&*out.setup);
  const auto dir = ::swlio::test::MakeTempDir("live-drive");
  out.config = LiveDriveConfig(dir, drive.dds_domain);
  if (drive.adjust_config) drive.adjust_config(&out.config);
  out.speed = kSanitized ? 0.5 : drive.speed;
  RuntimeOptions options;
  options.T_imu_lidar = out.setup->lidar.T_imu_lidar;
  options.time_scale = out.speed;
  options.record_dir = drive.record_dir;
  options.stamp_clocks = drive.stamp_clocks;
  auto rt = Runtime::Create(out.config, options, &out.error);
  if (!rt) return out;
  auto participant = ipc::Participant::Create(out.config.ipc, &out.error);
  if (!participant) return out;
  ipc::SubscriberOptions reader;
  reader.history_depth = 4000;  // 10 s of poses: the count must not depend on this thread's luck
  auto subscriber = ipc::Subscriber::Create(*participant, out.config.ipc, reader, &out.error);
  if (!subscriber) return out;

  out.daemon_time = rt->time_scale();
  rt->Start();
  sim::LiveOptions live;
  live.msop_port = rt->msop_port();
  live.difop_port = rt->difop_port();
  live.speed = out.speed;
  live.pty_link = out.config.imu.device;
  live.start_delay_s = 0.5;
  // Under a sanitizer, ray casting is slower than streaming at 0.5x. Cast on the fly, the
  // sensors' clocks would slow down whenever the simulator falls behind (a TSan CI run
  // streamed at 0.22x while the daemon was told 0.5x, and diverged).
  live.precast = kSanitized;
  live.out_dir = dir / "sim";
  live.faults = drive.faults;
  if (drive.on_sim_start) {
    live.on_start = [&drive, speed = out.speed](int64_t start_ns) {
      drive.on_sim_start(start_ns, speed);
    };
  }
  volatile bool stop = false;  // never set: RunLive's flag is for signal handlers, not threads
  std::atomic<bool> sim_done{false};
  std::string sim_error;
  std::thread simulator([&] {
    out.sim_ok = sim::RunLive(*out.setup, live, &stop, &out.stats, &sim_error);
    sim_done = true;
  });
  std::vector<std::pair<int64_t, HealthSnapshot>> snapshots;
  auto take = [&] {
    for (auto& p : subscriber->TakePoses()) out.poses.push_back(std::move(p));
    out.odometry += subscriber->TakeOdometry().size();
    for (auto& h : subscriber->TakeHealth()) out.published_health.push_back(std::move(h));
    // Every topic must be taken: a sample left unread keeps the wait set triggered, and this
    // loop then spun, taking a snapshot every few microseconds on a core the daemon needs.
    subscriber->TakePaths();
    for (auto& s : subscriber->TakeSweeps()) out.sweeps.push_back(std::move(s));
    subscriber->TakeMaps();
    subscriber->TakeOdomOdometry();
    subscriber->TakeTf();
    subscriber->TakeTfStatic();
  };
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration<double>(drive.duration_s / out.speed + 60.0);
  int64_t next_snapshot_ns = 0;
  while (!sim_done && std::chrono::steady_clock::now() < deadline) {
    subscriber->Wait(100'000'000);
    take();
    out.ready = out.ready || rt->Ready();
    if (const int64_t now = MonotonicNowNs(); now >= next_snapshot_ns) {  // every 100 ms
      snapshots.emplace_back(now, rt->Snapshot());
      next_snapshot_ns = now + 100'000'000;
      // What swliod's supervision loop does every second (health.csv, incident events).
      if (snapshots.size() % 10 == 0) rt->ObserveForRecording(snapshots.back().second, {});
    }
  }
  simulator.join();
  // A late simulator makes the sensors' clocks run slower than the speed the daemon was told
  // (LiveOptions::precast): say so, so that a failure it causes is not taken for the daemon's.
  if (out.stats.max_lateness_ms > 100.0) {
    std::cout << "[ note ] the simulator sent up to " << out.stats.max_lateness_ms << " ms late\n";
  }
  rt->Stop();  // the consumers drain what the rx threads received
  subscriber->Wait(200'000'000);
  take();
  out.final = rt->Snapshot();
  if (!out.sim_ok) out.error = sim_error;
  for (auto& [t_ns, s] : snapshots) out.health.push_back({out.SimTime(t_ns), std::move(s)});
  return out;
}

}  // namespace swlio::daemon::test

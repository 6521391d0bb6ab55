// swlio_daemon_latency: the daemon's end-to-end latencies, measured as a user would see them.
// The simulator streams a drive live (LiDAR over UDP to 127.0.0.1, IMU Xbus frames written on a
// pseudo-terminal) into the daemon's Runtime, which publishes over DDS (loopback XML); a
// subscriber in this process takes every sample.
//
// - IMU → pose: from the moment the simulator wrote the frame carrying a sample on the pty
//   (CLOCK_MONOTONIC just before write(2), recorded by the simulator) to the moment the
//   subscriber took the IMU-rate pose of that sample. The pose's stamp is the sample's time on
//   the host clock; it is matched to the nearest simulated sample (400 Hz, so unambiguous).
// - sweep → odometry: from the sweep's end (its last firing; the last packet leaves ≈ 1.3 ms
//   later) to the odometry's take. An upper bound of "last packet sent → odometry received".
//
// Usage: swlio_daemon_latency [--scenario S] [--seed N] [--duration S] [--dds-config XML]
//                             [--domain N]   (default 200)
//                             [--realtime]   (config/swlio.yaml's thread priorities, SCHED_FIFO)
//                             [--plain]      (without config/swlio.yaml's nice values)
//                             [--echo-dds-config XML]
// --echo-dds-config: the subscriber is a swlio-echo process with that XML instead of this
// process (samples then cross loopback UDP; with DDS Security they are encrypted, which an
// in-process reader would skip). Take times come from its --latency CSV (CLOCK_MONOTONIC is
// common to both processes). docs/dds-security.md compares --dds-config daemon.xml
// --echo-dds-config consumer.xml with the loopback XML for both.
// Prints the percentiles and the daemon's drop counters; run on an otherwise idle machine.

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "live/sim_live.h"
#include "scenarios/sim_setup.h"
#include "sensors/imu_sim.h"
#include "swlio/daemon/config/config_loader.h"
#include "swlio/daemon/runtime/runtime.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/subscriber.h"

extern char** environ;

namespace {

struct Taken {
  int64_t stamp_ns;
  int64_t take_ns;
};

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

void Report(const char* what, const std::vector<double>& ms) {
  std::printf("%s: n %zu, p50 %.3f ms, p90 %.3f ms, p99 %.3f ms, max %.3f ms\n", what, ms.size(),
              Percentile(ms, 0.5), Percentile(ms, 0.9), Percentile(ms, 0.99), Percentile(ms, 1.0));
}

/// IMU → pose latencies: each pose matched to its simulated sample's pty write time.
std::vector<double> PoseLatencies(const std::vector<Taken>& poses,
                                  const std::vector<swlio::sim::SimImuSample>& imu,
                                  const std::vector<int64_t>& written_ns,
                                  int64_t start_ns) {
  std::vector<double> ms;
  for (const Taken& p : poses) {
    const int64_t t_sim = p.stamp_ns - start_ns;
    auto it = std::lower_bound(imu.begin(), imu.end(), t_sim,
                               [](const auto& s, int64_t t) { return s.t_true_ns < t; });
    if (it == imu.end()) continue;
    if (it != imu.begin() && t_sim - std::prev(it)->t_true_ns < it->t_true_ns - t_sim) --it;
    if (std::llabs(it->t_true_ns - t_sim) > 1'000'000) continue;  // not matched within 1 ms
    const auto k = static_cast<size_t>(it - imu.begin());
    if (k >= written_ns.size() || written_ns[k] == 0) continue;
    ms.push_back(static_cast<double>(p.take_ns - written_ns[k]) * 1e-6);
  }
  return ms;
}

/// swlio-echo reading pose and odometry into `csv` (its --latency rows), in its own process.
class EchoProcess {
 public:
  EchoProcess(const std::string& xml, int64_t domain, const std::string& csv) {
    const std::vector<std::string> argv = {
        SWLIO_ECHO_PATH, "--dds-config",  xml,       "--domain",  std::to_string(domain),
        "--topics",      "pose,odometry", "--quiet", "--latency", csv};
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (posix_spawn(&pid_, args[0], nullptr, nullptr, args.data(), environ) != 0) pid_ = -1;
  }
  ~EchoProcess() { Stop(); }
  bool running() const { return pid_ > 0; }
  /// SIGTERM: swlio-echo stops, closes its CSV and exits 0.
  bool Stop() {
    if (pid_ <= 0) return false;
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
  }

 private:
  pid_t pid_ = -1;
};

/// The pose and odometry rows of a swlio-echo --latency CSV as (stamp, receive_steady_ns).
void ReadEchoCsv(const std::string& csv, std::vector<Taken>* poses, std::vector<Taken>* odometry) {
  std::ifstream in(csv);
  std::string line;
  std::getline(
      in, line);  // topic,stamp_ns,source_realtime_ns,receive_realtime_ns,receive_steady_ns,...
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string topic, stamp, source, receive_realtime, receive_steady;
    std::getline(row, topic, ',');
    std::getline(row, stamp, ',');
    std::getline(row, source, ',');
    std::getline(row, receive_realtime, ',');
    std::getline(row, receive_steady, ',');
    const Taken t{std::stoll(stamp), std::stoll(receive_steady)};
    if (topic == "pose") poses->push_back(t);
    if (topic == "odometry") odometry->push_back(t);
  }
}

/// config/swlio.yaml's thread scheduling (`realtime`): its nice values, and with `realtime`
/// its SCHED_FIFO priorities too; `plain`: none of it (every thread at nice 0).
swlio::daemon::RealtimeConfig ShippedScheduling(bool realtime, bool plain) {
  const auto loaded = swlio::daemon::LoadConfigFile(SWLIO_SOURCE_DIR "/config/swlio.yaml");
  if (!loaded.ok()) {
    std::fprintf(stderr, "%s", loaded.ErrorReport().c_str());
    std::exit(1);
  }
  swlio::daemon::RealtimeConfig r = loaded.config.realtime;
  r.enabled = realtime;
  r.lock_memory = false;
  if (plain) r.threads.clear();
  return r;
}

int Run(const std::string& scenario,
        int seed,
        int64_t domain,
        double duration_s,
        const std::string& xml,
        const std::string& echo_xml,
        bool realtime,
        bool plain) {
  const auto setup = swlio::sim::MakeSimSetup(scenario, static_cast<uint64_t>(seed), duration_s);
  if (!setup) return 1;
  swlio::daemon::DaemonConfig config;
  config.lidar.bind_address = "127.0.0.1";
  config.lidar.msop_port = 0;
  config.lidar.difop_port = 0;
  config.imu.device = "/tmp/swlio_daemon_latency.pty";
  config.imu.configure_on_start = false;
  config.ipc.domain_id = domain;
  config.ipc.dds_config_file = xml;
  config.ipc.stamp_clock = "monotonic";  // stamps against the simulator's CLOCK_MONOTONIC
  config.realtime = ShippedScheduling(realtime, plain);
  swlio::daemon::RuntimeOptions options;
  options.T_imu_lidar = setup->lidar.T_imu_lidar;
  std::string error;
  auto rt = swlio::daemon::Runtime::Create(config, options, &error);
  if (!rt) return std::fprintf(stderr, "%s\n", error.c_str()), 1;
  std::unique_ptr<swlio::ipc::Participant> participant;
  std::unique_ptr<swlio::ipc::Subscriber> subscriber;
  std::unique_ptr<EchoProcess> echo;
  const std::string echo_csv = "/tmp/swlio_daemon_latency_echo.csv";
  if (echo_xml.empty()) {
    participant = swlio::ipc::Participant::Create(config.ipc, &error);
    if (participant) {
      swlio::ipc::SubscriberOptions only;  // what is measured; an untaken topic spins Wait
      only.topics.fill(false);
      only.topics[static_cast<size_t>(swlio::ipc::Topic::kPose)] = true;
      only.topics[static_cast<size_t>(swlio::ipc::Topic::kOdometry)] = true;
      subscriber = swlio::ipc::Subscriber::Create(*participant, config.ipc, only, &error);
    }
    if (!subscriber) return std::fprintf(stderr, "%s\n", error.c_str()), 1;
  } else {
    echo = std::make_unique<EchoProcess>(echo_xml, config.ipc.domain_id, echo_csv);
    if (!echo->running()) return std::fprintf(stderr, "cannot start %s\n", SWLIO_ECHO_PATH), 1;
  }
  rt->Start();
  swlio::sim::LiveOptions live;
  live.msop_port = rt->msop_port();
  live.difop_port = rt->difop_port();
  live.pty_link = config.imu.device;
  // A separate reader first needs discovery (and with DDS Security, the handshakes).
  live.start_delay_s = echo ? 3.0 : 1.0;
  std::vector<int64_t> written_ns;
  live.imu_write_ns = &written_ns;
  volatile bool stop = false;
  swlio::sim::LiveStats stats;
  std::atomic<bool> done{false};
  std::thread sim([&] {
    if (!swlio::sim::RunLive(*setup, live, &stop, &stats, &error))
      std::fprintf(stderr, "%s\n", error.c_str());
    done = true;
  });
  std::vector<Taken> poses, odometry;
  while (!done) {
    if (!subscriber) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      continue;
    }
    subscriber->Wait(100'000'000);
    for (const auto& r : subscriber->TakePoses())
      poses.push_back({r.msg.t_ns, r.receive_steady_ns});
    for (const auto& r : subscriber->TakeOdometry())
      odometry.push_back({r.msg.t_ns, r.receive_steady_ns});
  }
  sim.join();
  if (echo) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the last samples in flight
    if (!echo->Stop()) return std::fprintf(stderr, "swlio-echo failed\n"), 1;
    ReadEchoCsv(echo_csv, &poses, &odometry);
  }
  const swlio::daemon::HealthSnapshot s = rt->Snapshot();
  rt->Stop();
  const auto imu = swlio::sim::SimulateImu(*setup->trajectory, setup->imu, setup->seed);
  Report("IMU frame written on the pty -> pose taken",
         PoseLatencies(poses, imu, written_ns, stats.start_ns));
  std::vector<double> odom_ms;
  for (const Taken& o : odometry)
    odom_ms.push_back(static_cast<double>(o.take_ns - o.stamp_ns) * 1e-6);
  Report("sweep end -> odometry taken", odom_ms);
  std::printf("simulator: %llu datagrams, %llu IMU bytes, worst send lateness %.2f ms\n",
              static_cast<unsigned long long>(stats.udp_sent),
              static_cast<unsigned long long>(stats.imu_bytes), stats.max_lateness_ms);
  std::printf("daemon: %s\n", swlio::daemon::HealthReporter().StatusLine(s).c_str());
  std::printf("daemon drops: %llu\n",
              static_cast<unsigned long long>(swlio::daemon::TotalDrops(s)));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "swlio_daemon_latency: end-to-end latencies of the daemon on a live simulated drive"};
  std::string scenario = "short", xml = SWLIO_SOURCE_DIR "/config/cyclonedds-loopback.xml";
  int seed = 1;
  // 200: apart from every test's (101..199; tests/daemon/runtime/live_drive.h). Two benchmarks
  // on one domain read each other's samples: give a second one another id.
  int64_t domain = 200;
  double duration_s = 30.0;
  app.add_option("--scenario", scenario)->capture_default_str();
  app.add_option("--seed", seed)->capture_default_str();
  app.add_option("--domain", domain, "DDS domain id")->capture_default_str();
  app.add_option("--duration", duration_s, "seconds of the drive")->capture_default_str();
  app.add_option("--dds-config", xml)->capture_default_str();
  std::string echo_xml;
  app.add_option("--echo-dds-config", echo_xml,
                 "read in a swlio-echo process with this XML (default: in this process)");
  bool realtime = false, plain = false;
  app.add_flag("--realtime", realtime, "SCHED_FIFO for the rx, propagator and publisher threads");
  app.add_flag("--plain", plain, "no nice values either: every thread at nice 0");
  CLI11_PARSE(app, argc, argv);
  return Run(scenario, seed, domain, duration_s, xml, echo_xml, realtime, plain);
}

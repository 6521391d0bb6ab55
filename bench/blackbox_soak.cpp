// The black box's bounds over a long run, fast (issue 35): the recorder as the daemon runs it
// (record.ring, its incidents thread) takes RS-LiDAR-16 and Xsens traffic at its real rates
// (840 datagrams of 1248 bytes and 400 frames of 60 bytes per sensor second), on a time base N×
// faster than the host (time_scale.h, as swliod --time-scale for a simulator at N×), with an
// incident event every --incident-every-s sensor seconds. Every 100 ms it reads the ring's
// size from the recorder's counters, every 5 s from the disk, and prints the largest of each
// against max_disk_mb, with what was kept. Not a Google Benchmark: one run's figures.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <thread>

#include <time.h>

#include "swlio/core/time.h"
#include "swlio/daemon/blackbox/ring_segments.h"
#include "swlio/daemon/recording/recorder.h"

namespace {

using swlio::daemon::DaemonConfig;
using swlio::daemon::Recorder;

struct Options {
  std::string dir = "/tmp/swlio-blackbox-soak";
  double minutes = 30.0;  ///< sensor time
  double speed = 10.0;
  double incident_every_s = 300.0;
  DaemonConfig config;
};

int64_t RealtimeNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return ts.tv_sec * 1'000'000'000LL + ts.tv_nsec;
}

/// One sensor second of traffic, pushed at `t_ns` (host).
void PushSecond(Recorder* r, int64_t t_ns, uint64_t* refused) {
  swlio::daemon::LidarPacket p;
  p.size = 1248;
  for (int i = 0; i < 840; ++i) {
    p.t_rx_ns = t_ns;
    *refused += r->lidar_queue().Push(p) ? 0 : 1;
  }
  swlio::daemon::SerialChunk c;
  c.size = 60;
  for (int i = 0; i < 400; ++i) {
    c.t_rx_ns = t_ns;
    *refused += r->serial_queue().Push(c) ? 0 : 1;
  }
}

int Run(Options& opt) {
  std::filesystem::remove_all(opt.dir);
  opt.config.record.ring = true;
  opt.config.record.directory = opt.dir;
  swlio::daemon::RecordingSetup setup;
  setup.config = &opt.config;
  setup.time = {swlio::daemon::MonotonicNowNs(), opt.speed};
  setup.version = "soak";
  std::string error;
  auto recorder = Recorder::CreateRing(setup, &error);
  if (!recorder) return std::fprintf(stderr, "%s\n", error.c_str()), 1;
  std::atomic<bool> stop{false}, stop_keeper{false};
  std::thread rec([&] { recorder->Run(stop, {}); });
  std::thread keeper([&] { recorder->incidents()->Run(stop_keeper, {}); });
  const int64_t start = swlio::daemon::MonotonicNowNs();
  const auto seconds = static_cast<int64_t>(opt.minutes * 60.0);
  const auto step_ns = static_cast<int64_t>(1e9 / opt.speed);
  uint64_t refused = 0, most = 0, most_disk = 0;
  for (int64_t s = 0; s < seconds; ++s) {
    const int64_t due = start + s * step_ns;
    for (int64_t now = swlio::daemon::MonotonicNowNs(); now < due;
         now = swlio::daemon::MonotonicNowNs()) {
      std::this_thread::sleep_for(
          std::chrono::nanoseconds(std::min<int64_t>(due - now, 20'000'000)));
      most = std::max(most, recorder->counters().ring_bytes);
    }
    PushSecond(recorder.get(), due, &refused);
    if (s > 0 && s % static_cast<int64_t>(opt.incident_every_s) == 0)
      recorder->AddEvent(
          {setup.time.ToDaemon(due), RealtimeNowNs(), "mark", "soak " + std::to_string(s)});
    if (s % 50 == 0)
      most_disk = std::max(most_disk, swlio::daemon::DirectoryBytes(opt.dir + "/ring"));
  }
  stop = true;
  rec.join();
  stop_keeper = true;
  keeper.join();
  const auto c = recorder->counters();
  std::printf(
      "{\"sensor_minutes\": %.1f, \"speed\": %.1f, \"wall_s\": %.1f, \"max_disk_mb\": %lld, "
      "\"ring_mb_max_counted\": %.2f, \"ring_mb_max_on_disk\": %.2f, \"segments_deleted\": %llu, "
      "\"lidar_packets\": %llu, \"refused_pushes\": %llu, \"stopped\": %s, \"incidents_kept\": "
      "%llu, \"incidents_removed\": %llu, \"incidents_mb\": %.1f}\n",
      opt.minutes, opt.speed, static_cast<double>(swlio::daemon::MonotonicNowNs() - start) * 1e-9,
      static_cast<long long>(opt.config.record.max_disk_mb), static_cast<double>(most) / 1e6,
      static_cast<double>(most_disk) / 1e6, static_cast<unsigned long long>(c.segments_deleted),
      static_cast<unsigned long long>(c.lidar_packets), static_cast<unsigned long long>(refused),
      c.stopped ? "true" : "false", static_cast<unsigned long long>(c.incidents.kept),
      static_cast<unsigned long long>(c.incidents.removed),
      static_cast<double>(swlio::daemon::DirectoryBytes(opt.dir + "/incidents")) / 1e6);
  return most <= static_cast<uint64_t>(opt.config.record.max_disk_mb) * 1'000'000 ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"swlio_blackbox_soak: the black box's bounds over a long run at N× speed"};
  Options opt;
  auto& r = opt.config.record;
  r.max_disk_mb = 256;
  r.incidents_max_count = 3;
  app.add_option("--dir", opt.dir, "record.directory (emptied first)")->capture_default_str();
  app.add_option("--minutes", opt.minutes, "sensor minutes")->capture_default_str();
  app.add_option("--speed", opt.speed, "sensor seconds per host second")->capture_default_str();
  app.add_option("--incident-every-s", opt.incident_every_s, "sensor s")->capture_default_str();
  app.add_option("--max-disk-mb", r.max_disk_mb, "record.max_disk_mb")->capture_default_str();
  app.add_option("--ring-minutes", r.ring_minutes, "record.ring_minutes")->capture_default_str();
  app.add_option("--incidents-max-count", r.incidents_max_count)->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  return Run(opt);
}

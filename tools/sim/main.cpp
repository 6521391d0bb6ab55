// swlio-sim: simulated substation drives with ground truth, to a recording folder or live.

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "scenarios.h"
#include "sim_dump.h"
#include "sim_live.h"
#include "sim_recording.h"

namespace {

volatile bool g_stop = false;
void OnSignal(int) { g_stop = true; }

int RunFile(const swlio::sim::SimSetup& setup, const std::string& out) {
  const auto t0 = std::chrono::steady_clock::now();
  swlio::sim::RecordingStats stats;
  std::string error;
  if (!swlio::sim::WriteRecording(setup, out, &stats, &error)) {
    std::cerr << "swlio-sim: " << error << "\n";
    return 1;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "{\"scenario\": \"%s\", \"seed\": %llu, \"duration_s\": %.3f, \"length_m\": %.2f, "
      "\"msop_packets\": %llu, \"difop_packets\": %llu, \"valid_returns\": %llu, "
      "\"imu_frames\": %llu, \"groundtruth_poses\": %llu, \"generation_s\": %.2f}\n",
      setup.scenario.name.c_str(), static_cast<unsigned long long>(setup.seed),
      swlio::sim::SimDuration(setup), setup.trajectory->length_m(),
      static_cast<unsigned long long>(stats.msop_packets),
      static_cast<unsigned long long>(stats.difop_packets),
      static_cast<unsigned long long>(stats.valid_returns),
      static_cast<unsigned long long>(stats.imu_frames),
      static_cast<unsigned long long>(stats.gt_poses), secs);
  return 0;
}

int Run(int argc, char** argv) {
  CLI::App app{
      "swlio-sim: simulated substation drives (RS-LiDAR-16 + Xsens MTi) with ground truth"};
  std::string scenario = "short";
  uint64_t seed = 1;
  std::string out;
  double duration = 0.0;
  bool live = false, list = false;
  std::string dump_dir;
  swlio::sim::LiveOptions live_opts;
  app.add_option("--scenario", scenario, "short | loop943 | degenerate | aggressive");
  app.add_option("--seed", seed, "world and noise seed");
  app.add_option("--out", out, "output folder");
  app.add_option("--duration", duration, "cut the drive after this many seconds");
  app.add_flag("--list", list, "list the scenarios and exit");
  app.add_option("--dump-world", dump_dir, "write world.csv and route.csv to this folder, exit");
  app.add_flag("--live", live, "stream in real time: UDP to 127.0.0.1 and a pseudo-terminal");
  app.add_option("--speed", live_opts.speed, "live: N× real time")->check(CLI::Range(0.1, 50.0));
  app.add_option("--msop-port", live_opts.msop_port, "live: UDP port for MSOP");
  app.add_option("--difop-port", live_opts.difop_port, "live: UDP port for DIFOP");
  app.add_option("--pty-link", live_opts.pty_link, "live: symlink to the IMU pty");
  app.add_option("--start-delay", live_opts.start_delay_s, "live: seconds before streaming");
  CLI11_PARSE(app, argc, argv);

  if (list) {
    for (const auto& name : swlio::sim::ScenarioNames()) {
      std::printf("%-12s %s\n", name.c_str(), swlio::sim::MakeScenario(name)->description.c_str());
    }
    return 0;
  }
  auto setup = swlio::sim::MakeSimSetup(
      scenario, seed, duration > 0.0 ? std::optional<double>(duration) : std::nullopt);
  if (!setup) {
    std::cerr << "swlio-sim: unknown scenario '" << scenario << "' (see --list)\n";
    return 2;
  }
  if (!dump_dir.empty()) {
    std::string error;
    if (!swlio::sim::DumpWorldAndRoute(*setup, dump_dir, &error)) {
      std::cerr << "swlio-sim: " << error << "\n";
      return 1;
    }
    return 0;
  }
  if (!live) {
    if (out.empty()) {
      std::cerr << "swlio-sim: --out DIR is required\n";
      return 2;
    }
    return RunFile(*setup, out);
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  live_opts.out_dir = out;
  swlio::sim::LiveStats stats;
  std::string error;
  if (!swlio::sim::RunLive(*setup, live_opts, &g_stop, &stats, &error)) {
    std::cerr << "swlio-sim: " << error << "\n";
    return 1;
  }
  std::printf(
      "{\"udp_sent\": %llu, \"udp_errors\": %llu, \"imu_bytes\": %llu, "
      "\"imu_bytes_dropped\": %llu, \"max_lateness_ms\": %.3f}\n",
      static_cast<unsigned long long>(stats.udp_sent),
      static_cast<unsigned long long>(stats.udp_errors),
      static_cast<unsigned long long>(stats.imu_bytes),
      static_cast<unsigned long long>(stats.imu_bytes_dropped), stats.max_lateness_ms);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "swlio-sim: " << e.what() << "\n";
    return 2;
  }
}

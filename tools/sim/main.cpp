// swlio-sim: simulated substation drives with ground truth, to a recording folder or live.

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "disturb/apply_disturbances.h"
#include "live/sim_live.h"
#include "recording/sim_recording.h"
#include "scenarios/scenarios.h"
#include "scenarios/sim_dump.h"
#include "scenarios/sim_laps.h"

namespace {

volatile bool g_stop = false;
void OnSignal(int) { g_stop = true; }

/// "START:DURATION" in simulation seconds.
swlio::sim::TimeWindow ParseWindow(const std::string& text) {
  const std::string what = "expected two numbers (seconds) as A:B, got '" + text + "'";
  const size_t colon = text.find(':');
  if (colon == std::string::npos) throw std::invalid_argument(what);
  try {
    size_t used_a = 0, used_b = 0;
    const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
    const swlio::sim::TimeWindow w{std::stod(a, &used_a), std::stod(b, &used_b)};
    if (used_a != a.size() || used_b != b.size()) throw std::invalid_argument(what);
    return w;
  } catch (const std::logic_error&) {  // stod: invalid_argument, out_of_range
    throw std::invalid_argument(what);
  }
}

std::vector<swlio::sim::TimeWindow> ParseWindows(const std::vector<std::string>& texts) {
  std::vector<swlio::sim::TimeWindow> out;
  out.reserve(texts.size());
  for (const std::string& t : texts) out.push_back(ParseWindow(t));
  return out;
}

/// "START:DURATION:METRES" (seconds, seconds, metres east).
swlio::sim::GnssJump ParseJump(const std::string& text) {
  const std::string what = "expected three numbers as START:DURATION:METRES, got '" + text + "'";
  const size_t a = text.find(':');
  const size_t b = a == std::string::npos ? a : text.find(':', a + 1);
  if (b == std::string::npos) throw std::invalid_argument(what);
  auto number = [&what](const std::string& part) {
    try {
      size_t used = 0;
      const double v = std::stod(part, &used);
      if (used != part.size()) throw std::invalid_argument(what);
      return v;
    } catch (const std::logic_error&) {  // stod: invalid_argument, out_of_range
      throw std::invalid_argument(what);
    }
  };
  return {number(text.substr(0, a)), number(text.substr(a + 1, b - a - 1)),
          number(text.substr(b + 1))};
}

/// The optional streams (GNSS items, wheel odometry) and the GNSS faults, for recordings and
/// live runs alike.
struct StreamArgs {
  bool no_gnss = false, no_wheel = false;
  std::vector<std::string> gnss_outages, gnss_jumps;

  void Add(CLI::App& app) {
    app.add_flag("--no-gnss", no_gnss, "no GnssPvtData items in the IMU stream");
    app.add_flag("--no-wheel", no_wheel, "no can.log (wheel odometry) in a recording");
    app.add_option("--gnss-outage", gnss_outages,
                   "fault: GNSS without a fix (fixType 0) during START:DURATION (s)");
    app.add_option("--gnss-jump", gnss_jumps,
                   "fault: GNSS positions METRES east during START:DURATION:METRES, "
                   "accuracy unchanged (an outlier)");
  }

  void Apply(swlio::sim::SimSetup* setup) const {
    if (no_gnss) setup->imu.gnss_pvt_period_s = 0.0;
    if (no_wheel) setup->wheel.enabled = false;
    setup->gnss.outages = ParseWindows(gnss_outages);
    for (const std::string& j : gnss_jumps) setup->gnss.jumps.push_back(ParseJump(j));
  }
};

/// The live mode's fault injection (sim_faults.h) on the command line.
struct FaultArgs {
  swlio::sim::LiveFaults faults;
  std::vector<std::string> lidar_outages, imu_gaps, unplugs, stalls, one_range;
  std::string difop, lidar_clock_jump;
  double imu_wrap_at_s = -1.0;

  void Add(CLI::App& app) {
    auto& f = faults;
    app.add_option("--udp-loss", f.udp_loss_fraction, "fault: MSOP loss fraction, in bursts")
        ->check(CLI::Range(0.0, 0.9));
    app.add_option("--udp-loss-burst", f.udp_loss_burst_packets, "fault: mean burst (datagrams)")
        ->check(CLI::Range(1.0, 1000.0));
    app.add_option("--lidar-outage", lidar_outages, "fault: no UDP during START:DURATION (s)");
    app.add_option("--imu-gap", imu_gaps, "fault: no IMU frames during START:DURATION");
    app.add_option("--serial-unplug", unplugs, "fault: the pty vanishes during START:DURATION");
    app.add_option("--serial-stall", stalls,
                   "fault: IMU bytes held during START:DURATION, then written at once");
    app.add_option("--one-range", one_range, "fault: every return at --one-range-m");
    app.add_option("--one-range-m", f.one_range_m, "range for --one-range (m)");
    app.add_option("--serial-garbage", f.serial_garbage_bytes_per_s, "fault: random bytes/s");
    app.add_option("--imu-nonfinite", f.imu_nonfinite_fraction, "fault: frames with NaN/Inf")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--difop", difop, "fault: missing | corrupt")
        ->check(CLI::IsMember({"missing", "corrupt"}));
    app.add_flag("--lidar-silent", f.lidar_silent, "fault: the LiDAR never sends");
    app.add_flag("--imu-silent", f.imu_silent, "fault: the IMU never sends");
    app.add_option("--lidar-clock-jump", lidar_clock_jump,
                   "fault: AT:STEP, the LiDAR clock steps by STEP s at AT s");
    app.add_option("--imu-wrap-at", imu_wrap_at_s,
                   "fault: the IMU's SampleTimeFine counter wraps at this time (s)");
  }

  /// Into the options and the sensors' clocks.
  void Apply(swlio::sim::SimSetup* setup, swlio::sim::LiveOptions* live) {
    faults.lidar_outages = ParseWindows(lidar_outages);
    faults.imu_gaps = ParseWindows(imu_gaps);
    faults.serial_unplugs = ParseWindows(unplugs);
    faults.serial_stalls = ParseWindows(stalls);
    faults.lidar_one_range = ParseWindows(one_range);
    faults.difop_missing = difop == "missing";
    faults.difop_corrupt = difop == "corrupt";
    faults.seed = setup->seed;
    if (!lidar_clock_jump.empty()) {
      const swlio::sim::TimeWindow w = ParseWindow(lidar_clock_jump);
      setup->lidar.clock.step_at_s = w.start_s;
      setup->lidar.clock.step_s = w.duration_s;
    }
    if (imu_wrap_at_s >= 0.0) swlio::sim::SetImuWrapAt(setup, imu_wrap_at_s);
    live->faults = faults;
  }
};

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
      "\"imu_frames\": %llu, \"groundtruth_poses\": %llu, \"gnss_items\": %llu, "
      "\"wheel_frames\": %llu, \"generation_s\": %.2f}\n",
      setup.scenario.name.c_str(), static_cast<unsigned long long>(setup.seed),
      swlio::sim::SimDuration(setup), setup.trajectory->length_m(),
      static_cast<unsigned long long>(stats.msop_packets),
      static_cast<unsigned long long>(stats.difop_packets),
      static_cast<unsigned long long>(stats.valid_returns),
      static_cast<unsigned long long>(stats.imu_frames),
      static_cast<unsigned long long>(stats.gt_poses),
      static_cast<unsigned long long>(stats.gnss_items),
      static_cast<unsigned long long>(stats.wheel_frames), secs);
  return 0;
}

int Run(int argc, char** argv) {
  CLI::App app{
      "swlio-sim: simulated substation drives (RS-LiDAR-16 + Xsens MTi) with ground truth"};
  std::string scenario = "short";
  uint64_t seed = 1;
  uint64_t world_seed = 0;
  std::string out;
  double duration = 0.0;
  int laps = 1;
  bool live = false, list = false;
  std::string dump_dir;
  swlio::sim::LiveOptions live_opts;
  app.add_option("--scenario", scenario,
                 "short | loop943 | degenerate | aggressive | revisit | calibration | field");
  app.add_option("--seed", seed, "world and noise seed");
  app.add_option("--world-seed", world_seed,
                 "draw the substation from this seed instead (a second drive in a mapped world)");
  app.add_option("--out", out, "output folder");
  app.add_option("--duration", duration, "cut the drive after this many seconds");
  double stand_start = 0.0;
  app.add_option("--stand-start", stand_start,
                 "seconds standing still before driving off (the scenario's own: 2)")
      ->check(CLI::Range(1.0, 3600.0));
  app.add_option("--laps", laps,
                 "drive a closed route (loop943) this many times; live: the first lap's rays "
                 "are cast before streaming and replayed (long runs at 10x)")
      ->check(CLI::Range(1, 100000));
  app.add_flag("--list", list, "list the scenarios and exit");
  app.add_option("--dump-world", dump_dir, "write world.csv and route.csv to this folder, exit");
  app.add_flag("--live", live, "stream in real time: UDP to 127.0.0.1 and a pseudo-terminal");
  app.add_option("--speed", live_opts.speed, "live: N× real time")->check(CLI::Range(0.1, 50.0));
  app.add_option("--msop-port", live_opts.msop_port, "live: UDP port for MSOP");
  app.add_option("--difop-port", live_opts.difop_port, "live: UDP port for DIFOP");
  app.add_option("--pty-link", live_opts.pty_link, "live: symlink to the IMU pty");
  app.add_option("--start-delay", live_opts.start_delay_s, "live: seconds before streaming");
  app.add_flag("--precast", live_opts.precast,
               "live: cast every LiDAR packet before streaming (about 1 MB per second of "
               "driving), so the stream keeps its schedule on a loaded machine");
  std::string disturb;
  app.add_option("--disturb", disturb,
                 "add field disturbances, comma-separated: people, vehicles, vibration, "
                 "mixed_pixels, rain, dust, dropouts, time_offset, temperature, all (the "
                 "scenario's own stay on: field has all)");
  double time_offset_ms = 0.0;
  app.add_option("--time-offset-ms", time_offset_ms,
                 "the time_offset disturbance with this offset (ms) instead of one drawn in "
                 "+-10 ms from the seed: IMU samples measure the motion this long before their "
                 "stamps")
      ->check(CLI::Range(-100.0, 100.0));
  std::string vibration_rms;
  app.add_option("--vibration-rms", vibration_rms,
                 "the vibration disturbance with these acceleration RMS (m/s^2) as REST:DRIVE "
                 "(standing, at 1 m/s) instead of drawn from the seed");
  uint64_t vibration_seed = 0;
  app.add_option("--vibration-seed", vibration_seed,
                 "the vibration disturbance with its tones (frequencies, axes, phases) drawn "
                 "from this seed instead of --seed: the same drive under another vibration");
  FaultArgs fault_args;
  fault_args.Add(app);
  StreamArgs stream_args;
  stream_args.Add(app);
  CLI11_PARSE(app, argc, argv);

  if (list) {
    for (const auto& name : swlio::sim::ScenarioNames()) {
      std::printf("%-12s %s\n", name.c_str(), swlio::sim::MakeScenario(name)->description.c_str());
    }
    return 0;
  }
  auto setup = swlio::sim::MakeSimSetup(
      scenario, seed, duration > 0.0 ? std::optional<double>(duration) : std::nullopt,
      app.count("--world-seed") > 0 ? std::optional<uint64_t>(world_seed) : std::nullopt,
      app.count("--stand-start") > 0 ? std::optional<double>(stand_start) : std::nullopt);
  if (!setup) {
    std::cerr << "swlio-sim: unknown scenario '" << scenario << "' (see --list)\n";
    return 2;
  }
  stream_args.Apply(&*setup);
  {
    std::string error;
    auto set = swlio::sim::ParseDisturbanceList(disturb, &error);
    if (!set) {
      std::cerr << "swlio-sim: --disturb: " << error << "\n";
      return 2;
    }
    swlio::sim::DisturbanceOverrides overrides;
    if (app.count("--time-offset-ms") > 0) {
      overrides.time_offset_s = time_offset_ms * 1e-3;
      set->Add(swlio::sim::Disturbance::kTimeOffset);
    }
    if (!vibration_rms.empty()) {
      const swlio::sim::TimeWindow w = ParseWindow(vibration_rms);  // two numbers, A:B
      if (w.start_s < 0.0 || w.duration_s < 0.0) {
        std::cerr << "swlio-sim: --vibration-rms: negative RMS\n";
        return 2;
      }
      overrides.vibration_rest_rms_mps2 = w.start_s;
      overrides.vibration_drive_rms_mps2 = w.duration_s;
      set->Add(swlio::sim::Disturbance::kVibration);
    }
    if (app.count("--vibration-seed") > 0) {
      overrides.vibration_seed = vibration_seed;
      set->Add(swlio::sim::Disturbance::kVibration);
    }
    swlio::sim::ApplyDisturbances(&*setup, *set, overrides);
  }
  if (std::string error; !swlio::sim::RepeatRoute(&*setup, laps, &error)) {
    std::cerr << "swlio-sim: --laps: " << error << "\n";
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
  fault_args.Apply(&*setup, &live_opts);
  swlio::sim::LiveStats stats;
  std::string error;
  if (!swlio::sim::RunLive(*setup, live_opts, &g_stop, &stats, &error)) {
    std::cerr << "swlio-sim: " << error << "\n";
    return 1;
  }
  const swlio::sim::FaultCounts& f = stats.faults;
  auto u = [](uint64_t v) { return static_cast<unsigned long long>(v); };
  std::printf(
      "{\"udp_sent\": %llu, \"udp_errors\": %llu, \"imu_bytes\": %llu, "
      "\"imu_bytes_dropped\": %llu, \"imu_bytes_delayed\": %llu, \"imu_backlog_max_bytes\": %llu, "
      "\"imu_backlog_max_wait_ms\": %.1f, \"lateness_ms\": {\"p50\": %.3f, \"p99\": %.3f, "
      "\"max\": %.3f}, \"late_sends\": %llu, \"faults\": {\"msop_lost\": %llu, "
      "\"msop_withheld\": %llu, \"difop_dropped\": %llu, \"difop_corrupted\": %llu, "
      "\"msop_one_range\": %llu, \"imu_withheld\": %llu, \"imu_nonfinite\": %llu, "
      "\"garbage_bytes\": %llu, \"unplugs\": %llu}}\n",
      u(stats.udp_sent), u(stats.udp_errors), u(stats.imu_bytes), u(stats.imu_bytes_dropped),
      u(stats.imu_bytes_delayed), u(stats.imu_backlog_max_bytes), stats.imu_backlog_max_wait_ms,
      stats.lateness_p50_ms, stats.lateness_p99_ms, stats.max_lateness_ms, u(stats.late_sends),
      u(f.msop_lost), u(f.msop_withheld), u(f.difop_dropped), u(f.difop_corrupted),
      u(f.msop_one_range), u(f.imu_withheld), u(f.imu_nonfinite), u(f.garbage_bytes), u(f.unplugs));
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

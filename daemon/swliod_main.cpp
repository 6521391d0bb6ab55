// swliod: the localization daemon. main() only parses the command line and wires modules.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "swlio/daemon/config/config_files.h"
#include "swlio/daemon/config/config_loader.h"
#include "swlio/daemon/config/config_printer.h"
#include "swlio/daemon/runtime/daemon_main.h"
#include "swlio/daemon/runtime/logging.h"

namespace {

/// The name of `path` in messages: "-" is standard input.
std::string DisplayName(const std::string& path) { return path == "-" ? "<stdin>" : path; }

/// `path`, or standard input for "-". Relative paths inside standard input resolve against the
/// current directory (a printed configuration has none: --print-config writes them absolute).
swlio::daemon::LoadedConfig LoadFileOrStdin(const std::string& path) {
  if (path != "-") return swlio::daemon::LoadConfigFile(path);
  std::ostringstream text;
  text << std::cin.rdbuf();
  return swlio::daemon::LoadConfigText(text.str(), DisplayName(path),
                                       std::filesystem::current_path());
}

/// Loads and validates `path` (schema, ranges, referenced files); prints every problem.
bool LoadChecked(const std::string& path, swlio::daemon::DaemonConfig* config) {
  const swlio::daemon::LoadedConfig loaded = LoadFileOrStdin(path);
  const std::string name = DisplayName(path);
  if (!loaded.ok()) {
    std::cerr << loaded.ErrorReport();
    std::cerr << name << ": " << loaded.errors.size() << " error(s)\n";
    return false;
  }
  const std::vector<std::string> file_problems = swlio::daemon::CheckReferencedFiles(loaded.config);
  for (const std::string& problem : file_problems) std::cerr << name << ": " << problem << "\n";
  if (!file_problems.empty()) return false;
  *config = loaded.config;
  return true;
}

/// --map, --save-map and --localize over the file's `map` section, validated again.
bool ApplyMapFlags(const std::string& map_path,
                   const std::string& save_map,
                   bool localize,
                   swlio::daemon::DaemonConfig* config) {
  if (!map_path.empty()) config->map.load_path = map_path;
  if (!save_map.empty()) config->map.save_path = save_map;
  if (localize) config->map.localize = true;
  bool ok = true;
  for (const swlio::ConfigIssue& issue : config->map.Validate()) {
    std::cerr << "swliod: map." << issue.key << ": " << issue.reason << "\n";
    ok = false;
  }
  return ok;
}

int Run(int argc, char** argv) {
  swlio::daemon::BlockStopSignals();  // before any thread exists (spdlog, DDS, ours)
  CLI::App app{"swliod: LiDAR-inertial localization daemon"};
  std::string check_config, print_config, config_path;
  double run_for_s = 0.0;
  bool no_dds = false;
  double time_scale = 1.0;
  std::string record_dir, map_path, save_map;
  bool localize = false;
  auto* check = app.add_option("--check-config", check_config,
                               "Validate a configuration file (- for standard input), print "
                               "every problem with its line, and exit");
  auto* print = app.add_option("--print-config", print_config,
                               "Print the effective configuration of a file (- for standard "
                               "input) as YAML: every key, defaults filled in, paths absolute; "
                               "--check-config accepts it")
                    ->excludes(check);
  app.add_option("--config", config_path, "Configuration file (YAML) to run with")
      ->excludes(check)
      ->excludes(print);
  app.add_option("--run-for", run_for_s, "Stop after this many seconds (0: until a signal)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--no-dds", no_dds, "Run without DDS (nothing is published)");
  app.add_option("--time-scale", time_scale,
                 "The sensors' clocks run this many times faster than the host (the simulator "
                 "at --speed N); 1 on a robot")
      ->check(CLI::Range(0.1, 50.0));
  app.add_option("--record", record_dir,
                 "Record every sensor's raw bytes with host receive times into this folder "
                 "(lidar.pcap, imu.xbus, imu.rx.csv, manifest.yaml; replay with swlio-replay)");
  app.add_option("--save-map", save_map,
                 "With loop closure: save the pose graph as a map here when stopping, and its "
                 "merged cloud as FILE.pcd (overrides map.save_path)");
  app.add_option("--map", map_path, "A saved map to localize in (overrides map.load_path)");
  app.add_flag("--localize", localize,
               "Localize in the saved map: relocalization from place descriptors, then tracking "
               "against the fixed map; no pose is published until localized (map.localize)");
  CLI11_PARSE(app, argc, argv);

  if (!check_config.empty()) {
    swlio::daemon::DaemonConfig config;
    if (!LoadChecked(check_config, &config)) return 1;
    std::cout << DisplayName(check_config) << ": OK\n";
    return 0;
  }
  if (!print_config.empty()) {
    swlio::daemon::DaemonConfig config;
    if (!LoadChecked(print_config, &config)) return 1;
    std::cout << swlio::daemon::PrintConfig(config);
    return 0;
  }
  if (config_path.empty()) {
    std::cerr << "swliod: give --config FILE (or --check-config FILE, --print-config FILE)\n";
    return 2;
  }
  swlio::daemon::DaemonConfig config;
  // EX_CONFIG (sysexits.h): the unit's RestartPreventExitStatus= does not restart a daemon
  // whose configuration is wrong (systemd/README.md).
  constexpr int kExitConfig = 78;
  if (!LoadChecked(config_path, &config)) return kExitConfig;
  if (!ApplyMapFlags(map_path, save_map, localize, &config)) return kExitConfig;
  std::string error;
  if (!swlio::daemon::SetupLogging(config.logging, &error)) {
    std::cerr << "swliod: " << error << "\n";
    return 1;
  }
  swlio::daemon::RuntimeOptions options;
  options.dds = !no_dds;
  options.time_scale = time_scale;
  options.record_dir = record_dir;
  return swlio::daemon::RunDaemon(config, options, static_cast<int64_t>(run_for_s * 1e9));
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "swliod: " << e.what() << "\n";
    return 2;
  }
}

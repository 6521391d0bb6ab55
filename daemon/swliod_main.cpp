// swliod: the localization daemon. main() only parses the command line and wires modules.

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>
#include <vector>

#include "swlio/daemon/config_files.h"
#include "swlio/daemon/config_loader.h"

namespace {

int Run(int argc, char** argv) {
  CLI::App app{"swliod: LiDAR-inertial localization daemon"};
  std::string check_config;
  app.add_option("--check-config", check_config,
                 "Validate a configuration file, print every problem with its line, and exit")
      ->required();
  CLI11_PARSE(app, argc, argv);

  const swlio::daemon::LoadedConfig loaded = swlio::daemon::LoadConfigFile(check_config);
  if (!loaded.ok()) {
    std::cerr << loaded.ErrorReport();
    std::cerr << check_config << ": " << loaded.errors.size() << " error(s)\n";
    return 1;
  }
  const std::vector<std::string> file_problems = swlio::daemon::CheckReferencedFiles(loaded.config);
  for (const std::string& problem : file_problems)
    std::cerr << check_config << ": " << problem << "\n";
  if (!file_problems.empty()) return 1;
  std::cout << check_config << ": OK\n";
  return 0;
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

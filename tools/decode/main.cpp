// swlio-decode: decode captured sensor data (pcap, raw Xbus bytes, candump logs) into JSON
// summaries and CSV files. Each format is a subcommand in its own file.

#include <iostream>

#include "decode_command.h"

namespace swlio::tools {

std::vector<DecodeCommandFactory>& DecodeCommands() {
  static std::vector<DecodeCommandFactory> commands;
  return commands;
}

}  // namespace swlio::tools

namespace {

int Run(int argc, char** argv) {
  CLI::App app{"swlio-decode: decode captured LiDAR, Xsens and CAN data"};
  app.require_subcommand(1);
  int exit_code = 0;
  for (const auto& add : swlio::tools::DecodeCommands()) add(app, &exit_code);
  CLI11_PARSE(app, argc, argv);
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "swlio-decode: " << e.what() << "\n";
    return 2;
  }
}

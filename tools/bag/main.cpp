// swlio-bag: ROS bags as swlio reads them (rosbag2 .db3 and MCAP files or folders, ROS 1 .bag).
//
//   swlio-bag info FILE      storage, per-topic type, count, rate and span, and warnings:
//                            types swlio does not read, messages that do not decode, header
//                            stamps out of order or repeated, damage the reader skipped.
//
// Exit codes: 0 read to the end, 1 a read error stopped it, 2 not openable / bad arguments.

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "bag_summary.h"
#include "swlio/drivers/bag/bag_open.h"

namespace {

int Info(const std::string& path, bool decode) {
  std::string error;
  auto reader = swlio::drivers::bag::OpenBag(path, {}, &error);
  if (!reader) {
    std::cerr << "swlio-bag: " << error << "\n";
    return 2;
  }
  const swlio::tools::BagSummary s = swlio::tools::Summarize(*reader, decode);
  std::cout << swlio::tools::FormatSummary(s);
  return s.read_error.empty() ? 0 : 1;
}

int Run(int argc, char** argv) {
  CLI::App app{"swlio-bag: ROS bags (rosbag2 .db3 / MCAP, ROS 1 .bag) as swlio reads them"};
  app.require_subcommand(1);
  std::string path;
  bool no_decode = false;
  int exit_code = 0;
  CLI::App* info = app.add_subcommand("info", "topics, types, counts, time span and warnings");
  info->add_option("FILE", path, "bag file or rosbag2 folder")->required();
  info->add_flag("--no-decode", no_decode, "list only: skip decoding (no stamp or layout checks)");
  info->callback([&] { exit_code = Info(path, !no_decode); });
  CLI11_PARSE(app, argc, argv);
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "swlio-bag: " << e.what() << "\n";
    return 2;
  }
}

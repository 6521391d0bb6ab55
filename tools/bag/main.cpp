// swlio-bag: ROS bags as swlio reads them (rosbag2 .db3 and MCAP files or folders, ROS 1 .bag).
//
//   swlio-bag info FILE      storage, per-topic type, count, rate and span, and warnings:
//                            types swlio does not read, messages that do not decode, header
//                            stamps out of order or repeated, damage the reader skipped.
//   swlio-bag export DIR OUT.mcap
//                            a recording folder as a rosbag2 MCAP (bag_export.h).
//
// Exit codes: 0 read to the end, 1 a read error stopped it, 2 not openable / bad arguments.

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "bag_export.h"
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

int Export(const std::string& dir,
           const std::string& out,
           const std::string& compression,
           const std::string& config) {
  swlio::tools::ExportOptions options;
  options.config = config;
  swlio::drivers::bag::ParseCompression(compression, &options.compression);  // checked by CLI11
  swlio::tools::ExportCounts n;
  std::string error;
  if (!swlio::tools::ExportRecording(dir, out, options, &n, &error)) {
    std::cerr << "swlio-bag export: " << error << "\n";
    return 1;
  }
  std::cout << out << ": " << n.clouds << " PointCloud2, " << n.imu << " Imu, " << n.gnss
            << " NavSatFix, " << n.wheel << " Odometry messages\n"
            << swlio::tools::RigConfigPath(out) << ": the rig (swlio-run " << out << " --config "
            << swlio::tools::RigConfigPath(out) << ")\n";
  return 0;
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
  std::string out, compression = "zstd", config;
  CLI::App* exp = app.add_subcommand("export", "a recording folder as a rosbag2 MCAP");
  exp->add_option("DIR", path, "recording folder (swlio-sim --out, swliod --record)")
      ->required()
      ->check(CLI::ExistingDirectory);
  exp->add_option("OUT", out, "MCAP file to write")->required();
  exp->add_option("--compression", compression, "MCAP chunk compression")
      ->check(CLI::IsMember({"zstd", "lz4", "none"}))
      ->capture_default_str();
  exp->add_option("--config", config,
                  "daemon configuration (LiDAR model and range limits, IMU baud, extrinsics "
                  "when the recording's manifest has none)");
  exp->callback([&] { exit_code = Export(path, out, compression, config); });
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

// swlio-decode helios16p FILE.pcap [--msop-port N] [--difop-port N] [--cut-angle D]
//                                  [--summary] [--points OUT.csv]
// The shared LiDAR pipeline (lidar_decode.h) with the RS-Helios-16P decoder: JSON summary with
// the common keys plus the DIFOP fields; CSV of every valid point in rs_driver's frame
// (x forward, y left, z up, with its lens offset unless --lens-offset says otherwise).

#include <iostream>
#include <memory>
#include <string>

#include "decode_command.h"
#include "json_writer.h"
#include "lidar_decode.h"
#include "swlio/drivers/helios16p_decoder.h"

namespace swlio::tools {
namespace {

struct HeliosArgs {
  std::string file;
  LidarDecodeOptions options;
  drivers::Helios16pOptions decoder;
  bool summary = false;
};

void WriteDifop(const drivers::Helios16pDecoder& decoder, JsonWriter& json) {
  const drivers::Helios16pInfo& info = decoder.Info();
  json.Key("difop").BeginObject();
  json.Key("received").Value(info.difop_seen);
  json.Key("rpm").Value(info.rpm);
  json.Key("msop_port").Value(info.msop_port);
  json.Key("difop_port").Value(info.difop_port);
  json.Key("return_mode_byte").Value(info.return_mode_byte);
  json.Key("calibration_from_difop").Value(info.calibration_from_difop);
  std::array<double, 16> vertical{};
  for (size_t i = 0; i < vertical.size(); ++i) vertical[i] = decoder.VerticalCdeg(i) / 100.0;
  json.Key("vertical_angles_deg").Array(std::span<const double>(vertical));
  json.EndObject();
}

int Run(HeliosArgs& args) {
  drivers::Helios16pDecoder decoder(args.decoder);
  args.options.pcap_path = args.file;
  LidarDecodeResult result;
  std::string error;
  if (!RunLidarDecode(decoder, args.options, &result, &error)) {
    std::cerr << "swlio-decode helios16p: " << error << "\n";
    return 1;
  }
  if (args.summary || args.options.points_csv.empty()) {
    JsonWriter json(std::cout);
    json.BeginObject();
    json.Key("model").Value("helios16p");
    json.Key("lens_offset_m").Value(args.decoder.lens_offset_m);
    WriteLidarSummary(result, json);
    WriteDifop(decoder, json);
    json.EndObject();
    std::cout << "\n";
  }
  return 0;
}

void AddHeliosCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<HeliosArgs>();
  CLI::App* cmd = app.add_subcommand("helios16p", "RS-Helios-16P pcap (MSOP/DIFOP)");
  cmd->add_option("file", args->file, "capture file (pcap or pcapng)")->required();
  cmd->add_option("--msop-port", args->options.data_port, "MSOP UDP port")->capture_default_str();
  cmd->add_option("--difop-port", args->options.info_port, "DIFOP UDP port")->capture_default_str();
  cmd->add_option("--cut-angle", args->options.cut_angle_deg, "sweep cut azimuth, degrees")
      ->check(CLI::Range(0.0, 359.999));
  cmd->add_option("--lens-offset", args->decoder.lens_offset_m,
                  "optical-centre offset along the firing azimuth, m (default: rs_driver's RX)")
      ->check(CLI::Range(0.0, 0.1))
      ->capture_default_str();
  cmd->add_flag("--summary", args->summary, "print the JSON summary (default without --points)");
  cmd->add_option("--points", args->options.points_csv, "write every valid point to this CSV");
  cmd->callback([args, exit_code] { *exit_code = Run(*args); });
}

// NOLINTNEXTLINE(cert-err58-cpp): start-up registration; bad_alloc here may terminate.
const DecodeCommandRegistrar kHeliosRegistrar(AddHeliosCommand);

}  // namespace
}  // namespace swlio::tools

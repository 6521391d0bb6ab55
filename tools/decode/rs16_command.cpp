// swlio-decode rs16: decode an RS-LiDAR-16 pcap (MSOP + DIFOP) into a JSON summary and,
// optionally, a CSV of every valid point (metres, in rs_driver's frame: x forward, y left,
// z up, with its lens offset unless --lens-offset says otherwise).

#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include "decode_command.h"
#include "json_writer.h"
#include "lidar_decode.h"
#include "swlio/drivers/rs16_decoder.h"

namespace swlio::tools {
namespace {

struct Rs16Args {
  std::string file;
  uint16_t msop_port = 6699;
  uint16_t difop_port = 7788;
  double cut_angle_deg = 0.0;
  double min_range_m = 0.0;
  double max_range_m = std::numeric_limits<double>::infinity();
  double lens_offset_m = drivers::rs16::kLensRxM;
  bool msop_port_given = false;
  bool summary = false;
  std::string points_csv;
};

void WriteDifop(const drivers::Rs16Decoder& decoder, JsonWriter& json) {
  const drivers::Rs16DifopInfo& info = decoder.difop();
  json.Key("difop").BeginObject();
  json.Key("received").Value(decoder.has_difop());
  json.Key("rpm").Value(info.rpm);
  json.Key("msop_port").Value(info.msop_dst_port);
  json.Key("difop_port").Value(info.difop_dst_port);
  json.Key("return_mode")
      .Value(info.return_mode == drivers::ReturnMode::kDual        ? "dual"
             : info.return_mode == drivers::ReturnMode::kLast      ? "last"
             : info.return_mode == drivers::ReturnMode::kStrongest ? "strongest"
                                                                   : "unknown");
  json.Key("supports_dual_return").Value(info.supports_dual_return);
  json.Key("distance_resolution_m").Value(decoder.distance_resolution_m());
  json.Key("has_vertical_calibration").Value(info.has_vertical_calibration);
  // Angles in use, by laser channel as transmitted (DIFOP calibration, else config defaults).
  json.Key("vertical_angles_deg").Array(std::span<const double>(decoder.vertical_deg_by_channel()));
  json.Key("ring_of_channel").Array(std::span<const uint16_t>(decoder.ring_of_channel()));
  json.EndObject();
}

int Run(const Rs16Args& args) {
  drivers::LidarConfig config;
  config.msop_port = args.msop_port;
  config.difop_port = args.difop_port;
  config.min_range_m = args.min_range_m;
  config.max_range_m = args.max_range_m;
  drivers::Rs16DecoderOptions decoder_options;
  decoder_options.lens_offset_m = args.lens_offset_m;
  drivers::Rs16Decoder decoder(config, decoder_options);
  LidarDecodeOptions options;
  options.pcap_path = args.file;
  options.data_port = args.msop_port;
  options.info_port = args.difop_port;
  options.cut_angle_deg = args.cut_angle_deg;
  options.points_csv = args.points_csv;
  // Without --msop-port, use the port the unit's own DIFOP names (the real capture: 2244).
  if (!args.msop_port_given && AdoptFirstInfoPacket(decoder, options) &&
      decoder.difop().msop_dst_port != 0) {
    options.data_port = decoder.difop().msop_dst_port;
  }
  LidarDecodeResult result;
  std::string error;
  if (!RunLidarDecode(decoder, options, &result, &error)) {
    std::cerr << "swlio-decode rs16: " << error << "\n";
    return 1;
  }
  if (args.summary || args.points_csv.empty()) {
    JsonWriter json(std::cout);
    json.BeginObject();
    json.Key("model").Value("rs16");
    json.Key("lens_offset_m").Value(args.lens_offset_m);
    WriteLidarSummary(result, json);
    WriteDifop(decoder, json);
    json.EndObject();
    std::cout << "\n";
  }
  return 0;
}

void AddRs16Command(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<Rs16Args>();
  CLI::App* cmd = app.add_subcommand("rs16", "RS-LiDAR-16 pcap (MSOP/DIFOP)");
  cmd->add_option("file", args->file, "capture file (pcap or pcapng)")->required();
  cmd->add_option("--msop-port", args->msop_port,
                  "UDP destination port of MSOP packets (default: as the DIFOP says, else 6699)")
      ->capture_default_str();
  cmd->add_option("--difop-port", args->difop_port, "UDP destination port of DIFOP packets")
      ->capture_default_str();
  cmd->add_option("--cut-angle", args->cut_angle_deg, "sweep cut azimuth, degrees [0, 360)")
      ->check(CLI::Range(0.0, 359.999))
      ->capture_default_str();
  cmd->add_option("--min-range", args->min_range_m, "drop returns closer than this, m")
      ->capture_default_str();
  cmd->add_option("--max-range", args->max_range_m, "drop returns farther than this, m");
  cmd->add_option("--lens-offset", args->lens_offset_m,
                  "optical-centre offset along the firing azimuth, m (default: rs_driver's RX; "
                  "0: the manual's formula)")
      ->check(CLI::Range(0.0, 0.1))
      ->capture_default_str();
  cmd->add_flag("--summary", args->summary, "print the JSON summary (default without --points)");
  cmd->add_option("--points", args->points_csv, "write every valid point to this CSV file");
  cmd->callback([args, cmd, exit_code] {
    args->msop_port_given = cmd->count("--msop-port") > 0;
    *exit_code = Run(*args);
  });
}

// NOLINTNEXTLINE(cert-err58-cpp): start-up registration; bad_alloc here may terminate.
const DecodeCommandRegistrar kRs16Registrar(AddRs16Command);

}  // namespace
}  // namespace swlio::tools

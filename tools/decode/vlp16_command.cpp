// swlio-decode vlp16 FILE.pcap [--port N] [--cut-angle D] [--summary] [--points OUT.csv]
// The shared LiDAR pipeline (lidar_decode.h) with the VLP-16 decoder (no info packets): JSON
// summary with the common keys; CSV of every valid point (second returns of dual pairs
// included) in the frame of Velodyne's ROS driver (x forward, y left, z up).

#include <iostream>
#include <memory>
#include <string>

#include "decode_command.h"
#include "json_writer.h"
#include "lidar_decode.h"
#include "swlio/drivers/vlp16_decoder.h"

namespace swlio::tools {
namespace {

struct Vlp16Args {
  std::string file;
  LidarDecodeOptions options;
  drivers::Vlp16Options decoder;
  bool summary = false;
};

int Run(Vlp16Args& args) {
  drivers::Vlp16Decoder decoder(args.decoder);
  args.options.pcap_path = args.file;
  args.options.info_port = 0;  // Velodyne sends no DIFOP-like packets on this port
  LidarDecodeResult result;
  std::string error;
  if (!RunLidarDecode(decoder, args.options, &result, &error)) {
    std::cerr << "swlio-decode vlp16: " << error << "\n";
    return 1;
  }
  if (args.summary || args.options.points_csv.empty()) {
    JsonWriter json(std::cout);
    json.BeginObject();
    json.Key("model").Value("vlp16");
    json.Key("lens_offset_m").Value(args.decoder.lens_offset_m);
    WriteLidarSummary(result, json);
    json.EndObject();
    std::cout << "\n";
  }
  return 0;
}

void AddVlp16Command(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<Vlp16Args>();
  args->options.data_port = 2368;  // VLP-16 factory data port
  CLI::App* cmd = app.add_subcommand("vlp16", "Velodyne VLP-16 data-packet pcap");
  cmd->add_option("file", args->file, "capture file (pcap or pcapng)")->required();
  cmd->add_option("--port", args->options.data_port, "data UDP port")->capture_default_str();
  cmd->add_option("--cut-angle", args->options.cut_angle_deg, "sweep cut azimuth, degrees")
      ->check(CLI::Range(0.0, 359.999));
  cmd->add_option("--lens-offset", args->decoder.lens_offset_m,
                  "optical-centre offset along the firing azimuth, m (default: none, as "
                  "Velodyne's drivers)")
      ->check(CLI::Range(0.0, 0.1))
      ->capture_default_str();
  cmd->add_flag("--summary", args->summary, "print the JSON summary (default without --points)");
  cmd->add_option("--points", args->options.points_csv, "write every valid point to this CSV");
  cmd->callback([args, exit_code] { *exit_code = Run(*args); });
}

// NOLINTNEXTLINE(cert-err58-cpp): start-up registration; bad_alloc here may terminate.
const DecodeCommandRegistrar kVlp16Registrar(AddVlp16Command);

}  // namespace
}  // namespace swlio::tools

// swlio-decode vlp16 FILE.pcap [--port N] --summary
// Prints one JSON object: packet counts, valid returns (second returns of dual pairs included),
// returns per ring and scans.

#include <cstdio>
#include <string>

#include "decode_command.h"
#include "lidar_pcap_summary.h"
#include "swlio/drivers/vlp16_decoder.h"

namespace swlio::tools {
namespace {

int RunVlp16(const std::string& file, uint16_t port) {
  drivers::Vlp16Decoder dec;
  const auto s = SummarizeLidarPcap(file, dec, port, 0);
  if (!s.opened) {
    std::fprintf(stderr, "vlp16: cannot open %s\n", file.c_str());
    return 1;
  }
  std::printf("{\"model\": \"vlp16\", ");
  PrintSummaryKeys(s, "packets_data", "packets_info");
  std::printf("}\n");
  return 0;
}

const DecodeCommandRegistrar kRegistrar([](CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("vlp16", "Velodyne VLP-16 data-packet pcap");
  auto file = std::make_shared<std::string>();
  auto port = std::make_shared<uint16_t>(2368);
  auto summary = std::make_shared<bool>(false);
  cmd->add_option("file", *file, "pcap file")->required();
  cmd->add_option("--port", *port, "data UDP port (0: any)");
  cmd->add_flag("--summary", *summary, "print the JSON summary");
  cmd->callback([=] { *exit_code = RunVlp16(*file, *port); });
});

}  // namespace
}  // namespace swlio::tools

// swlio-decode helios16p FILE.pcap [--msop-port N] [--difop-port N] --summary
// Prints one JSON object: packet counts, valid returns, returns per ring, scans and the DIFOP
// fields (rpm, ports, return mode, the 16 vertical angles).

#include <cstdio>
#include <string>

#include "decode_command.h"
#include "lidar_pcap_summary.h"
#include "swlio/drivers/helios16p_decoder.h"

namespace swlio::tools {
namespace {

int RunHelios16p(const std::string& file, uint16_t msop_port, uint16_t difop_port) {
  drivers::Helios16pDecoder dec;
  const auto s = SummarizeLidarPcap(file, dec, msop_port, difop_port);
  if (!s.opened) {
    std::fprintf(stderr, "helios16p: cannot open %s\n", file.c_str());
    return 1;
  }
  const auto& info = dec.Info();
  std::printf("{\"model\": \"helios16p\", ");
  PrintSummaryKeys(s, "packets_msop", "packets_difop");
  std::printf(", \"difop\": {\"seen\": %s, \"rpm\": %u, \"msop_port\": %u, \"difop_port\": %u, ",
              info.difop_seen ? "true" : "false", info.rpm, info.msop_port, info.difop_port);
  std::printf("\"return_mode\": %u, \"calibration_from_difop\": %s, \"vertical_angles_deg\": [",
              info.return_mode_byte, info.calibration_from_difop ? "true" : "false");
  for (size_t i = 0; i < 16; ++i) {
    std::printf("%s%.2f", i == 0 ? "" : ", ", dec.VerticalCdeg(i) / 100.0);
  }
  std::printf("]}}\n");
  return 0;
}

const DecodeCommandRegistrar kRegistrar([](CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("helios16p", "RS-Helios-16P MSOP/DIFOP pcap");
  auto file = std::make_shared<std::string>();
  auto msop = std::make_shared<uint16_t>(6699);
  auto difop = std::make_shared<uint16_t>(7788);
  auto summary = std::make_shared<bool>(false);
  cmd->add_option("file", *file, "pcap file")->required();
  cmd->add_option("--msop-port", *msop, "MSOP UDP port (0: any)");
  cmd->add_option("--difop-port", *difop, "DIFOP UDP port (0: any)");
  cmd->add_flag("--summary", *summary, "print the JSON summary");
  cmd->callback([=] { *exit_code = RunHelios16p(*file, *msop, *difop); });
});

}  // namespace
}  // namespace swlio::tools

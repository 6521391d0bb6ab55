#pragma once
/// @file
/// The model-independent part of `swlio-decode <lidar model>`: read a pcap, split data and
/// info packets by UDP destination port, decode with any LidarPacketDecoder, assemble sweeps,
/// count, and optionally write every point to CSV. Reusable by the rs16, helios16p and vlp16
/// subcommands.

#include <cstdint>
#include <string>
#include <vector>

#include "json_writer.h"
#include "swlio/drivers/lidar_decoder.h"
#include "swlio/drivers/pcap_file.h"

namespace swlio::tools {

struct LidarDecodeOptions {
  std::string pcap_path;
  uint16_t data_port = 6699;
  uint16_t info_port = 7788;  ///< 0: the format has no info packets
  double cut_angle_deg = 0.0;
  std::string points_csv;  ///< empty: no CSV
};

struct LidarDecodeResult {
  uint64_t packets_data = 0;      ///< data packets decoded
  uint64_t packets_info = 0;      ///< info packets decoded
  uint64_t packets_rejected = 0;  ///< on a known port but not decodable (size, header, time)
  uint64_t scans = 0;
  uint64_t complete_scans = 0;
  uint64_t points = 0;  ///< valid returns
  uint64_t no_returns = 0;
  std::vector<uint64_t> points_per_ring = std::vector<uint64_t>(16, 0);
  uint64_t gaps = 0;
  uint64_t missing_packets = 0;
  uint64_t discontinuities = 0;
  drivers::PcapReadStats pcap;
  std::string pcap_error;  ///< non-empty when the file ended in a read error
};

/// Offline files allow what a live receiver cannot: adopt the first info packet's calibration
/// before decoding any data packet, so early packets do not use the config fallback angles.
/// Returns true when an info packet was found and decoded.
bool AdoptFirstInfoPacket(drivers::LidarPacketDecoder& decoder, const LidarDecodeOptions& options);

/// Runs the pipeline: adopts the file's first info packet, then decodes in file order.
/// `packets_info` counts the info packets met in that order. Returns false (and sets `error`) when
/// the file or CSV cannot be opened.
bool RunLidarDecode(drivers::LidarPacketDecoder& decoder,
                    const LidarDecodeOptions& options,
                    LidarDecodeResult* result,
                    std::string* error);

/// Writes the common summary keys into the object `json` is currently in.
void WriteLidarSummary(const LidarDecodeResult& result, JsonWriter& json);

}  // namespace swlio::tools

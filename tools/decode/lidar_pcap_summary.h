#pragma once
// Shared by the helios16p and vlp16 subcommands of swlio-decode: walks the UDP payloads of a
// pcap file (libpcap, Ethernet/IPv4 only), decodes them with a LidarPacketDecoder and counts
// packets, valid returns per ring and scans (cut where the block azimuth wraps past 0°).
// Meant to be replaced by the drivers' pcap reader and scan assembler once those are merged.

#include <pcap/pcap.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

#include "swlio/drivers/lidar_decoder.h"

namespace swlio::tools {

struct LidarPcapSummary {
  bool opened = false;
  uint64_t packets_data = 0;
  uint64_t packets_info = 0;
  uint64_t packets_other = 0;  ///< UDP on the chosen ports that is neither data nor info
  uint64_t decode_errors = 0;
  uint64_t scans = 0;   ///< azimuth segments holding returns (first and last partial)
  uint64_t points = 0;  ///< valid returns
  uint64_t second_returns = 0;
  std::array<uint64_t, 16> points_per_ring{};
};

/// `data_port`/`info_port` 0 means "any port".
inline LidarPcapSummary SummarizeLidarPcap(const std::string& path,
                                           drivers::LidarPacketDecoder& dec,
                                           uint16_t data_port,
                                           uint16_t info_port) {
  LidarPcapSummary sum;
  char err[PCAP_ERRBUF_SIZE] = {};
  pcap_t* pc = pcap_open_offline(path.c_str(), err);
  if (pc == nullptr) return sum;
  sum.opened = true;
  static drivers::LidarPacketDecoder::ReturnBuffer buf;
  float prev_az = -1.0f;
  pcap_pkthdr* hdr = nullptr;
  const u_char* d = nullptr;
  while (pcap_next_ex(pc, &hdr, &d) == 1) {
    const size_t n = hdr->caplen;
    if (n < 42 || d[12] != 0x08 || d[13] != 0x00 || d[23] != 17) continue;
    const size_t ihl = static_cast<size_t>(d[14] & 0x0F) * 4;
    if (n < 14 + ihl + 8) continue;
    const u_char* udp = d + 14 + ihl;
    const auto port = static_cast<uint16_t>((udp[2] << 8) | udp[3]);
    const std::span<const uint8_t> payload(udp + 8, n - 14 - ihl - 8);
    const auto kind = dec.Classify(payload);
    if (kind == drivers::LidarPacketKind::kInfo && (info_port == 0 || port == info_port)) {
      ++sum.packets_info;
      if (dec.DecodeInfo(payload) != drivers::DecodeStatus::kOk) ++sum.decode_errors;
      continue;
    }
    if (data_port != 0 && port != data_port) continue;
    if (kind != drivers::LidarPacketKind::kData) {
      ++sum.packets_other;
      continue;
    }
    ++sum.packets_data;
    drivers::LidarPacketSummary s;
    if (dec.DecodeData(payload, buf, &s) != drivers::DecodeStatus::kOk) {
      ++sum.decode_errors;
      continue;
    }
    // Block azimuths are monotonic (return azimuths are not: per-laser offsets), so a scan
    // starts where the packet's block azimuth wraps, within the packet or between packets.
    if (prev_az < 0.0f || s.first_azimuth_deg < prev_az ||
        s.last_azimuth_deg < s.first_azimuth_deg) {
      ++sum.scans;
    }
    prev_az = s.last_azimuth_deg;
    for (uint32_t i = 0; i < s.returns; ++i) {
      const auto& r = buf[i];
      ++sum.points;
      ++sum.points_per_ring[r.ring % 16];
      if (r.return_index == 1) ++sum.second_returns;
    }
  }
  pcap_close(pc);
  return sum;
}

/// Prints the common keys (no braces): "packets", "packets_info", ..., "points_per_ring".
inline void PrintSummaryKeys(const LidarPcapSummary& s,
                             const char* data_key,
                             const char* info_key) {
  std::printf("\"packets\": %llu, \"%s\": %llu, \"%s\": %llu, \"packets_other\": %llu, ",
              static_cast<unsigned long long>(s.packets_data) +
                  static_cast<unsigned long long>(s.packets_info),
              data_key, static_cast<unsigned long long>(s.packets_data), info_key,
              static_cast<unsigned long long>(s.packets_info),
              static_cast<unsigned long long>(s.packets_other));
  std::printf("\"decode_errors\": %llu, \"scans\": %llu, \"points\": %llu, ",
              static_cast<unsigned long long>(s.decode_errors),
              static_cast<unsigned long long>(s.scans), static_cast<unsigned long long>(s.points));
  std::printf("\"second_returns\": %llu, \"points_per_ring\": [",
              static_cast<unsigned long long>(s.second_returns));
  for (size_t i = 0; i < 16; ++i) {
    std::printf("%s%llu", i == 0 ? "" : ", ",
                static_cast<unsigned long long>(s.points_per_ring[i]));
  }
  std::printf("]");
}

}  // namespace swlio::tools

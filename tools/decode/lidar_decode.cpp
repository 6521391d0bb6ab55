// Pipeline shared by the LiDAR subcommands of swlio-decode: pcap → decoder → scan assembler.

#include "lidar_decode.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "swlio/drivers/scan_assembler.h"

namespace swlio::tools {
namespace {

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<FILE, FileCloser>;

void CountScan(const drivers::AssembledScan& s, LidarDecodeResult* r, FILE* csv) {
  ++r->scans;
  if (!s.scan.partial) ++r->complete_scans;
  for (const LidarPoint& p : s.scan.points) {
    if (p.ring >= r->points_per_ring.size()) r->points_per_ring.resize(p.ring + 1u, 0);
    ++r->points_per_ring[p.ring];
    if (csv == nullptr) continue;
    // Azimuth of the point itself, clockwise from +x (forward) seen from above, as the
    // sensor's; coordinates with the 9 digits that give back the decoder's float exactly.
    double azimuth_deg = std::atan2(-p.xyz_m.y(), p.xyz_m.x()) * 180.0 / std::numbers::pi;
    if (azimuth_deg < 0.0) azimuth_deg += 360.0;
    std::fprintf(csv, "%llu,%u,%.3f,%.9g,%.9g,%.9g,%.0f,%lld\n",
                 static_cast<unsigned long long>(s.scan.seq), static_cast<unsigned>(p.ring),
                 azimuth_deg, static_cast<double>(p.xyz_m.x()), static_cast<double>(p.xyz_m.y()),
                 static_cast<double>(p.xyz_m.z()), static_cast<double>(p.intensity),
                 static_cast<long long>(p.dt_ns));
  }
}

}  // namespace

bool AdoptFirstInfoPacket(drivers::LidarPacketDecoder& decoder, const LidarDecodeOptions& options) {
  if (options.info_port == 0) return false;
  drivers::PcapUdpFilter filter;
  filter.dst_ports = {options.info_port};
  std::string ignored;
  auto reader = drivers::PcapReader::Open(options.pcap_path, filter, &ignored);
  drivers::UdpDatagram d;
  while (reader && reader->Next(&d)) {
    if (decoder.Classify(d.payload) == drivers::LidarPacketKind::kInfo &&
        decoder.DecodeInfo(d.payload) == drivers::DecodeStatus::kOk) {
      return true;
    }
  }
  return false;
}

bool RunLidarDecode(drivers::LidarPacketDecoder& decoder,
                    const LidarDecodeOptions& options,
                    LidarDecodeResult* result,
                    std::string* error) {
  drivers::PcapUdpFilter filter;
  filter.dst_ports = {options.data_port};
  if (options.info_port != 0) filter.dst_ports.push_back(options.info_port);
  auto reader = drivers::PcapReader::Open(options.pcap_path, filter, error);
  if (!reader) return false;
  AdoptFirstInfoPacket(decoder, options);
  File csv;
  if (!options.points_csv.empty()) {
    csv.reset(std::fopen(options.points_csv.c_str(), "w"));
    if (!csv) {
      *error = "cannot create '" + options.points_csv + "'";
      return false;
    }
    std::fputs("scan,ring,azimuth_deg,x,y,z,intensity,t_offset_ns\n", csv.get());
  }
  drivers::ScanAssemblerConfig config;
  config.cut_angle_deg = options.cut_angle_deg;
  drivers::ScanAssembler assembler(config);
  auto update_nominal = [&] {
    const double rpm = decoder.Rpm();
    assembler.SetNominal(decoder.PacketsPerRevolution(),
                         rpm > 0.0 ? static_cast<int64_t>(std::llround(60e9 / rpm)) : 0);
  };
  update_nominal();
  drivers::LidarPacketDecoder::ReturnBuffer returns;
  drivers::AssembledScan scan;
  drivers::UdpDatagram d;
  while (reader->Next(&d)) {
    const auto kind = decoder.Classify(d.payload);
    if (d.dst_port == options.info_port && kind == drivers::LidarPacketKind::kInfo &&
        decoder.DecodeInfo(d.payload) == drivers::DecodeStatus::kOk) {
      ++result->packets_info;
      update_nominal();
      continue;
    }
    drivers::LidarPacketSummary summary;
    if (d.dst_port != options.data_port || kind != drivers::LidarPacketKind::kData ||
        decoder.DecodeData(d.payload, returns, &summary) != drivers::DecodeStatus::kOk) {
      ++result->packets_rejected;
      continue;
    }
    ++result->packets_data;
    result->points += summary.returns;
    result->no_returns += summary.no_returns;
    assembler.AddPacket(std::span(returns.data(), summary.returns), summary, d.t_ns);
    while (assembler.PopScan(&scan)) CountScan(scan, result, csv.get());
  }
  assembler.Flush();
  while (assembler.PopScan(&scan)) CountScan(scan, result, csv.get());
  result->gaps = assembler.stats().gaps;
  result->missing_packets = assembler.stats().missing_packets;
  result->discontinuities = assembler.stats().discontinuities;
  result->pcap = reader->stats();
  result->pcap_error = reader->error();
  if (csv && std::fflush(csv.get()) != 0) {
    *error = "cannot write '" + options.points_csv + "'";
    return false;
  }
  return true;
}

void WriteLidarSummary(const LidarDecodeResult& r, JsonWriter& json) {
  json.Key("packets_msop").Value(r.packets_data);
  json.Key("packets_difop").Value(r.packets_info);
  json.Key("packets_rejected").Value(r.packets_rejected);
  json.Key("scans").Value(r.scans);
  json.Key("complete_scans").Value(r.complete_scans);
  json.Key("points").Value(r.points);
  json.Key("no_returns").Value(r.no_returns);
  json.Key("points_per_ring").Array(r.points_per_ring);
  // Issue 3: "gaps" is the number of missing packets detected; gap_events counts the gaps.
  json.Key("gaps").Value(r.missing_packets);
  json.Key("gap_events").Value(r.gaps);
  json.Key("discontinuities").Value(r.discontinuities);
  json.Key("pcap").BeginObject();
  json.Key("records").Value(r.pcap.records);
  json.Key("udp").Value(r.pcap.udp);
  json.Key("filtered_out").Value(r.pcap.filtered_out);
  json.Key("malformed").Value(r.pcap.malformed);
  json.Key("error").Value(r.pcap_error);
  json.EndObject();
}

}  // namespace swlio::tools

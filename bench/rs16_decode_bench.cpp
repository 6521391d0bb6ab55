// RS-LiDAR-16 decode throughput on one core: packets/s for MSOP decoding alone and with scan
// assembly. Uses the real capture (shared/data/rs16_washing_house) when found via
// $SWLIO_DATA_DIR or ../shared/data from the working directory, else synthetic packets.
// Goal (issue 3): ≥ 100,000 packets/s.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/rs16_encoder.h"
#include "swlio/drivers/scan_assembler.h"

namespace {

using swlio::drivers::LidarConfig;
using swlio::drivers::LidarPacketDecoder;
using swlio::drivers::LidarPacketSummary;
using swlio::drivers::Rs16Decoder;

struct Packets {
  std::vector<std::vector<uint8_t>> msop;
  std::vector<uint8_t> difop;
  bool real = false;
};

Packets LoadPackets() {
  Packets p;
  const char* env = std::getenv("SWLIO_DATA_DIR");  // NOLINT(concurrency-mt-unsafe): single thread
  const std::filesystem::path dir = env != nullptr ? env : "../shared/data";
  const auto file = dir / "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap";
  std::string error;
  if (auto reader = swlio::drivers::PcapReader::Open(file.string(), {}, &error)) {
    swlio::drivers::UdpDatagram d;
    while (reader->Next(&d)) {
      if (d.dst_port == 2244) p.msop.emplace_back(d.payload.begin(), d.payload.end());
      if (d.dst_port == 7788 && p.difop.empty()) p.difop.assign(d.payload.begin(), d.payload.end());
    }
    p.real = !p.msop.empty();
  }
  if (p.real) return p;
  for (int k = 0; k < 750; ++k) {  // 10 synthetic revolutions
    swlio::drivers::Rs16MsopContent c;
    c.t_sensor_ns = 1'500'000'000'000'000'000 + k * 1'332'000LL;
    for (size_t b = 0; b < 12; ++b) {
      c.blocks[b].azimuth_deg = 0.3996 * static_cast<double>(12 * k + static_cast<int>(b));
      c.blocks[b].range_m.fill(7.5f);
    }
    std::vector<uint8_t> bytes(1248);
    swlio::drivers::EncodeRs16Msop(c, bytes);
    p.msop.push_back(std::move(bytes));
  }
  return p;
}

const Packets& TestPackets() {
  static const Packets packets = LoadPackets();
  return packets;
}

Rs16Decoder MakeDecoder(const Packets& packets) {
  LidarConfig config;
  Rs16Decoder decoder(config);
  if (!packets.difop.empty()) decoder.DecodeInfo(packets.difop);
  return decoder;
}

void BM_Rs16DecodeMsop(benchmark::State& state) {
  const Packets& packets = TestPackets();
  const Rs16Decoder decoder = MakeDecoder(packets);
  LidarPacketDecoder::ReturnBuffer buf;
  size_t i = 0;
  for (auto _ : state) {
    LidarPacketSummary s;
    decoder.DecodeData(packets.msop[i], buf, &s);
    benchmark::DoNotOptimize(s.returns);
    benchmark::DoNotOptimize(buf.data());
    if (++i == packets.msop.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(packets.real ? "real capture, packets/s" : "synthetic, packets/s");
}
BENCHMARK(BM_Rs16DecodeMsop);

void BM_Rs16DecodeAndAssemble(benchmark::State& state) {
  const Packets& packets = TestPackets();
  const Rs16Decoder decoder = MakeDecoder(packets);
  swlio::drivers::ScanAssemblerConfig config;
  config.packets_per_revolution = decoder.PacketsPerRevolution();
  swlio::drivers::ScanAssembler assembler(config);
  swlio::drivers::AssembledScan scan;
  LidarPacketDecoder::ReturnBuffer buf;
  size_t i = 0;
  for (auto _ : state) {
    LidarPacketSummary s;
    decoder.DecodeData(packets.msop[i], buf, &s);
    assembler.AddPacket(std::span(buf.data(), s.returns), s);
    while (assembler.PopScan(&scan)) benchmark::DoNotOptimize(scan.scan.points.data());
    if (++i == packets.msop.size()) i = 0;  // the wrap is a time discontinuity: a new sweep
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(packets.real ? "real capture, packets/s" : "synthetic, packets/s");
}
BENCHMARK(BM_Rs16DecodeAndAssemble);

}  // namespace

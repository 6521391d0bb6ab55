// Decode throughput of the RS-Helios-16P and VLP-16 packet decoders on one core (items/s =
// packets/s). Packets are synthetic but fully populated: every channel carries a valid return
// (fixed-seed pseudo-random ranges), the decoder's worst case; block azimuths advance as at
// 600 rpm.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

#include "swlio/drivers/bytes.h"
#include "swlio/drivers/helios16p_decoder.h"
#include "swlio/drivers/vlp16_decoder.h"

namespace {

using swlio::drivers::DecodeStatus;
using swlio::drivers::LidarPacketDecoder;
using swlio::drivers::LidarPacketSummary;
namespace bytes = swlio::drivers::bytes;

constexpr size_t kPackets = 64;

std::vector<std::vector<uint8_t>> HeliosPackets() {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> range(200, 40000);  // 0.5–100 m at 2.5 mm
  std::vector<std::vector<uint8_t>> pkts;
  uint32_t az = 0;
  for (size_t i = 0; i < kPackets; ++i) {
    std::vector<uint8_t> p(swlio::drivers::Helios16pDecoder::kPacketBytes, 0);
    const uint8_t id[4] = {0x55, 0xAA, 0x05, 0x5A};
    std::copy(id, id + 4, p.begin());
    bytes::WriteU32Be(p.data() + 26, static_cast<uint32_t>(i * 667));
    for (size_t b = 0; b < 12; ++b, az = (az + 20) % 36000) {
      uint8_t* blk = p.data() + 42 + 100 * b;
      blk[0] = 0xFF;
      blk[1] = 0xEE;
      bytes::WriteU16Be(blk + 2, static_cast<uint16_t>(az));
      for (size_t c = 0; c < 32; ++c) {
        bytes::WriteU16Be(blk + 4 + 3 * c, static_cast<uint16_t>(range(rng)));
        blk[4 + 3 * c + 2] = static_cast<uint8_t>(c * 7);
      }
    }
    pkts.push_back(std::move(p));
  }
  return pkts;
}

std::vector<std::vector<uint8_t>> Vlp16Packets(uint8_t mode) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> range(250, 50000);  // 0.5–100 m at 2 mm
  std::vector<std::vector<uint8_t>> pkts;
  uint32_t az = 0;
  for (size_t i = 0; i < kPackets; ++i) {
    std::vector<uint8_t> p(swlio::drivers::Vlp16Decoder::kPacketBytes, 0);
    for (size_t b = 0; b < 12; ++b) {
      uint8_t* blk = p.data() + 100 * b;
      blk[0] = 0xFF;
      blk[1] = 0xEE;
      bytes::WriteU16Le(blk + 2, static_cast<uint16_t>(az));
      if (mode != 0x39 || b % 2 == 1) az = (az + 40) % 36000;
      for (size_t c = 0; c < 32; ++c) {
        bytes::WriteU16Le(blk + 4 + 3 * c, static_cast<uint16_t>(range(rng)));
        blk[4 + 3 * c + 2] = static_cast<uint8_t>(c * 5);
      }
    }
    bytes::WriteU32Le(p.data() + 1200, static_cast<uint32_t>(i * 1327));
    p[1204] = mode;
    p[1205] = 0x22;
    pkts.push_back(std::move(p));
  }
  return pkts;
}

void Run(benchmark::State& state,
         const LidarPacketDecoder& dec,
         const std::vector<std::vector<uint8_t>>& pkts) {
  static LidarPacketDecoder::ReturnBuffer buf;
  size_t i = 0;
  uint64_t returns = 0;
  for (auto _ : state) {
    LidarPacketSummary s;
    if (dec.DecodeData(pkts[i], buf, &s) != DecodeStatus::kOk) state.SkipWithError("decode");
    returns += s.returns;
    benchmark::DoNotOptimize(buf.data());
    i = (i + 1) % pkts.size();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["returns_per_packet"] =
      static_cast<double>(returns) / static_cast<double>(state.iterations());
}

void BM_Helios16pDecode(benchmark::State& state) {
  const swlio::drivers::Helios16pDecoder dec;
  Run(state, dec, HeliosPackets());
}
BENCHMARK(BM_Helios16pDecode);

void BM_Vlp16DecodeStrongest(benchmark::State& state) {
  const swlio::drivers::Vlp16Decoder dec;
  Run(state, dec, Vlp16Packets(0x37));
}
BENCHMARK(BM_Vlp16DecodeStrongest);

void BM_Vlp16DecodeDual(benchmark::State& state) {
  const swlio::drivers::Vlp16Decoder dec;
  Run(state, dec, Vlp16Packets(0x39));
}
BENCHMARK(BM_Vlp16DecodeDual);

}  // namespace

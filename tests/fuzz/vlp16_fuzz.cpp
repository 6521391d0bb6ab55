// libFuzzer target: VLP-16 decoder on arbitrary bytes. Each input is fed raw, then forced into a
// well-framed 1206-byte packet (block flags, wrapped azimuths, product id, a valid return mode
// chosen by the input, timestamp within the hour) so the geometry and dual-return paths run on
// fuzzed contents. Invariants: no crash/UB, at most 384 returns, finite coordinates.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "swlio/drivers/vlp16_decoder.h"

namespace {

using swlio::drivers::DecodeStatus;
using swlio::drivers::LidarPacketDecoder;
using swlio::drivers::LidarPacketSummary;
using swlio::drivers::Vlp16Decoder;

void CheckReturns(const LidarPacketDecoder::ReturnBuffer& buf, const LidarPacketSummary& s) {
  if (s.returns > 384) std::abort();
  for (uint32_t i = 0; i < s.returns; ++i) {
    const auto& r = buf[i];
    if (!std::isfinite(r.x_m) || !std::isfinite(r.y_m) || !std::isfinite(r.z_m) || r.ring > 15 ||
        r.azimuth_deg < 0.0f || r.azimuth_deg >= 360.0f) {
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static LidarPacketDecoder::ReturnBuffer buf;
  const Vlp16Decoder dec;
  const std::span<const uint8_t> in(data, size);
  LidarPacketSummary s;
  (void)dec.Classify(in);
  if (dec.DecodeData(in, buf, &s) == DecodeStatus::kOk) CheckReturns(buf, s);

  std::array<uint8_t, Vlp16Decoder::kPacketBytes> pkt{};
  std::copy_n(data, std::min(size, pkt.size()), pkt.begin());
  for (size_t b = 0; b < 12; ++b) {
    uint8_t* blk = pkt.data() + 100 * b;
    blk[0] = 0xFF;
    blk[1] = 0xEE;
    blk[3] = static_cast<uint8_t>(blk[3] % 0x8C);  // little-endian azimuth < 35840
  }
  pkt[1203] = static_cast<uint8_t>(pkt[1203] % 0xD6);  // µs past the hour < 3.59e9
  pkt[1204] = static_cast<uint8_t>(0x37 + pkt[1204] % 3);
  pkt[1205] = 0x22;
  s = {};
  if (dec.DecodeData(pkt, buf, &s) != DecodeStatus::kOk) std::abort();
  CheckReturns(buf, s);
  return 0;
}

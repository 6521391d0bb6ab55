// libFuzzer target: RS-Helios-16P decoder on arbitrary bytes. Each input is fed raw (Classify,
// DecodeInfo, DecodeData), then forced into a well-framed DIFOP and MSOP (ids and block flags
// set, azimuths wrapped) so the calibration and geometry paths run on fuzzed contents.
// Invariants: no crash/UB, at most 384 returns per packet, finite coordinates.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "swlio/drivers/helios16p_decoder.h"

namespace {

using swlio::drivers::DecodeStatus;
using swlio::drivers::Helios16pDecoder;
using swlio::drivers::LidarPacketDecoder;
using swlio::drivers::LidarPacketSummary;

void CheckReturns(const LidarPacketDecoder::ReturnBuffer& buf, const LidarPacketSummary& s) {
  if (s.returns > 384) std::abort();
  for (uint32_t i = 0; i < s.returns; ++i) {
    const auto& r = buf[i];
    if (!std::isfinite(r.x_m) || !std::isfinite(r.y_m) || !std::isfinite(r.z_m) || r.ring > 15) {
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static LidarPacketDecoder::ReturnBuffer buf;
  Helios16pDecoder dec;
  const std::span<const uint8_t> in(data, size);
  LidarPacketSummary s;
  (void)dec.Classify(in);
  (void)dec.DecodeInfo(in);
  if (dec.DecodeData(in, buf, &s) == DecodeStatus::kOk) CheckReturns(buf, s);

  std::array<uint8_t, Helios16pDecoder::kPacketBytes> pkt{};
  std::copy_n(data, std::min(size, pkt.size()), pkt.begin());
  const uint8_t difop_id[8] = {0xA5, 0xFF, 0x00, 0x5A, 0x11, 0x11, 0x55, 0x55};
  std::copy_n(difop_id, 8, pkt.begin());
  (void)dec.DecodeInfo(pkt);

  const uint8_t msop_id[4] = {0x55, 0xAA, 0x05, 0x5A};
  std::copy_n(msop_id, 4, pkt.begin());
  pkt[20] = pkt[21] = 0;  // seconds < 2^32
  pkt[26] = 0;
  pkt[27] = static_cast<uint8_t>(pkt[27] % 0x0F);  // microseconds < 10^6
  for (size_t b = 0; b < 12; ++b) {
    uint8_t* blk = pkt.data() + 42 + 100 * b;
    blk[0] = 0xFF;
    blk[1] = 0xEE;
    blk[2] = static_cast<uint8_t>(blk[2] % 0x8C);  // azimuth < 0x8C00 = 35840
  }
  s = {};
  if (dec.DecodeData(pkt, buf, &s) == DecodeStatus::kOk) CheckReturns(buf, s);
  return 0;
}

// libFuzzer target: RS-LiDAR-16 decoder (MSOP + DIFOP) and the scan assembler.
// Input: one option byte (time format, cut angle, initial return mode), then 1248-byte packets
// back to back; a shorter tail is offered as a (wrong-size) packet too. Invariants checked:
// return count ≤ buffer, azimuth in [0, 360), finite coordinates, dt_ns ≥ 0, t_end ≥ t_start.
// Seeds: python3 tests/fuzz/make_seeds.py <data dir> <out dir> (real capture packets).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/scan_assembler.h"

namespace {

using namespace swlio::drivers;  // NOLINT

void Check(bool ok) {
  if (!ok) __builtin_trap();
}

void Drain(ScanAssembler& assembler, AssembledScan* scan) {
  while (assembler.PopScan(scan)) {
    Check(scan->scan.t_end_ns >= scan->scan.t_start_ns);
    for (const auto& p : scan->scan.points) Check(p.dt_ns >= 0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t options_byte = data[0];
  const std::span<const uint8_t> input(data + 1, size - 1);
  Rs16DecoderOptions options;
  options.time_format = static_cast<rs16::TimeFormat>(options_byte % 3);
  options.initial_return_mode = (options_byte & 0x80) ? ReturnMode::kDual : ReturnMode::kStrongest;
  LidarConfig config;
  config.min_range_m = 0.0;
  Rs16Decoder decoder(config, options);
  ScanAssemblerConfig assembler_config;
  assembler_config.cut_angle_deg = ((options_byte >> 2) & 0x1F) * 11.25;
  assembler_config.reserve_points = 0;
  ScanAssembler assembler(assembler_config);
  static LidarPacketDecoder::ReturnBuffer returns;
  static AssembledScan scan;
  for (size_t at = 0; at < input.size(); at += rs16::kPacketBytes) {
    const auto packet = input.subspan(at, std::min(rs16::kPacketBytes, input.size() - at));
    if (decoder.Classify(packet) == LidarPacketKind::kInfo) {
      decoder.DecodeInfo(packet);
      assembler.SetNominal(decoder.PacketsPerRevolution(),
                           static_cast<int64_t>(60e9 / decoder.Rpm()));
      continue;
    }
    LidarPacketSummary summary;
    if (decoder.DecodeData(packet, returns, &summary) != DecodeStatus::kOk) continue;
    Check(summary.returns + summary.no_returns == 384);
    for (uint32_t i = 0; i < summary.returns; ++i) {
      const LidarReturn& r = returns[i];
      Check(r.azimuth_deg >= 0.0f && r.azimuth_deg < 360.0f);
      Check(std::isfinite(r.x_m) && std::isfinite(r.y_m) && std::isfinite(r.z_m));
      Check(r.ring < 16 && r.slot < 384);
    }
    assembler.AddPacket(std::span(returns.data(), summary.returns), summary);
    Drain(assembler, &scan);
  }
  assembler.Flush();
  Drain(assembler, &scan);
  return 0;
}

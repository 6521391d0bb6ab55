// libFuzzer target for the CAN side: the candump line parser (with a format → parse round
// trip on every line it accepts) and the wheel-odometry decoder on layouts and frames built
// from the input. Any crash, sanitizer report or broken invariant (__builtin_trap) is a bug.
//
// Input: byte 0 selects the target. Even: the rest is one candump line. Odd: bytes 1–12 make a
// two-signal layout (start bit, length, order, sign per signal, ids), the rest is a sequence
// of 14-byte frames: id (4, little-endian), flags (1: extended, remote, error), dlc (1), data (8).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "swlio/drivers/bytes.h"
#include "swlio/drivers/candump_log.h"
#include "swlio/drivers/wheel_odom_decoder.h"

namespace {

using swlio::drivers::CandumpLineStatus;
using swlio::drivers::CandumpRecord;

void Check(bool ok) {
  if (!ok) __builtin_trap();
}

void FuzzCandumpLine(const uint8_t* data, size_t size) {
  const std::string_view line(reinterpret_cast<const char*>(data), size);
  CandumpRecord r;
  if (swlio::drivers::ParseCandumpLine(line, &r) != CandumpLineStatus::kFrame) return;
  Check(r.frame.dlc <= 8 && r.t_ns >= 0);
  std::array<char, swlio::drivers::kCandumpMaxLineBytes> buf{};
  const size_t n = swlio::drivers::FormatCandumpLine(r, buf);
  Check(n > 0 && n <= buf.size());
  CandumpRecord back;
  Check(swlio::drivers::ParseCandumpLine(std::string_view(buf.data(), n), &back) ==
        CandumpLineStatus::kFrame);
  Check(back.t_ns == r.t_ns / 1000 * 1000);
  Check(back.interface_name() == r.interface_name());
  Check(back.frame.id == r.frame.id && back.frame.extended == r.frame.extended &&
        back.frame.remote == r.frame.remote && back.frame.error == r.frame.error &&
        back.frame.dlc == r.frame.dlc);
  if (!r.frame.remote) Check(back.frame.data == r.frame.data);
}

swlio::drivers::CanSignalConfig SignalFrom(const uint8_t* p, const char* role) {
  swlio::drivers::CanSignalConfig s;
  s.role = role;
  s.start_bit = p[0] % 64;
  s.length_bits = 1 + p[1] % 64;
  s.byte_order = (p[2] & 1) != 0 ? "motorola" : "intel";
  s.is_signed = (p[2] & 2) != 0;
  s.extended = (p[2] & 4) != 0;
  s.can_id = (p[3] | (p[4] << 8)) & (s.extended ? 0x1FFFFFFF : 0x7FF);
  s.dlc = p[5] % 10;  // 9 is invalid on purpose
  s.scale = 0.001;
  return s;
}

void FuzzDecoder(const uint8_t* data, size_t size) {
  if (size < 12) return;
  swlio::drivers::CanConfig c;
  c.mode = (data[0] & 1) != 0 ? "twist" : "wheel_speeds";
  const bool twist = c.mode == "twist";
  c.signals = {SignalFrom(data, twist ? "linear_velocity" : "left_wheel_speed"),
               SignalFrom(data + 6, twist ? "angular_velocity" : "right_wheel_speed")};
  auto decoder = swlio::drivers::WheelOdomDecoder::Create(c);
  if (!decoder) return;
  data += 12;
  size -= 12;
  int64_t t_ns = 0;
  for (; size >= 14; data += 14, size -= 14) {
    swlio::drivers::CanFrame f;
    f.id = swlio::drivers::bytes::ReadU32Le(data) & 0x1FFFFFFF;
    f.extended = (data[4] & 1) != 0;
    f.remote = (data[4] & 2) != 0;
    f.error = (data[4] & 4) != 0;
    f.dlc = data[5];  // may exceed 8: must be counted, not read past the array
    for (size_t i = 0; i < 8; ++i) f.data[i] = data[6 + i];
    t_ns += data[4] * 1'000'000;
    const auto s = decoder->Decode(f, t_ns);
    if (s) {
      Check(std::isfinite(s->linear_velocity_mps) && std::isfinite(s->yaw_rate_radps));
      Check(s->t_ns == t_ns);
    }
  }
  const auto& n = decoder->counters();
  Check(n.frames == n.frames_used + n.unknown_id + n.bad_dlc + n.remote_or_error);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  if ((data[0] & 1) == 0) {
    FuzzCandumpLine(data + 1, size - 1);
  } else {
    FuzzDecoder(data + 1, size - 1);
  }
  return 0;
}

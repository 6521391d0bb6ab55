// Wheel-odometry decoder for chassis CAN frames. Protocol summary: the chassis is not a
// standard device, so its layout comes from config (can_config.h), expressed the way DBC files
// describe signals (Vector "DBC File Format Documentation" 1.0.1, section 8.1): a raw field of
// `length_bits` at a start bit, Intel (little-endian) or Motorola (big-endian) byte order,
// two's complement when signed, physical = raw · scale + offset. Classic CAN frames only
// (ISO 11898-1: ≤ 8 data bytes).
//
// Extraction treats the 8 data bytes as one 64-bit word read with the matching byte order
// (bytes.h helpers), so each field is a single shift and mask:
//   Intel:    word = little-endian u64; the field's LSB is word bit `start_bit`.
//   Motorola: word = big-endian u64; linear bit L = 0 is byte 0 bit 7 (the DBC MSB numbering
//             maps start bit s to L = 8·(s/8) + 7 − s%8), and the field is L .. L+len−1,
//             so it sits at word bit 64 − L − len.

#include "swlio/drivers/wheel_odom_decoder.h"

#include <cstdlib>

#include "swlio/core/time.h"
#include "swlio/drivers/bytes.h"

namespace swlio::drivers {

std::optional<CompiledCanSignal> CompileCanSignal(const CanSignalConfig& c) {
  if (!c.Validate().empty()) return std::nullopt;
  const bool motorola = c.byte_order == "motorola";
  const int64_t start =
      c.start_bit >= 0 ? c.start_bit : (motorola ? c.byte_offset * 8 + 7 : c.byte_offset * 8);
  int64_t shift = 0;
  int64_t last_linear = 0;
  if (motorola) {
    const int64_t msb_linear = (start / 8) * 8 + (7 - start % 8);
    last_linear = msb_linear + c.length_bits - 1;
    shift = 64 - msb_linear - c.length_bits;
  } else {
    last_linear = start + c.length_bits - 1;
    shift = start;
  }
  CompiledCanSignal s;
  s.id = static_cast<uint32_t>(c.can_id);
  s.extended = c.extended;
  s.motorola = motorola;
  s.is_signed = c.is_signed;
  s.length_bits = static_cast<uint8_t>(c.length_bits);
  s.shift = static_cast<uint8_t>(shift);
  s.min_dlc = static_cast<uint8_t>(last_linear / 8 + 1);
  s.exact_dlc = static_cast<uint8_t>(c.dlc);
  s.scale = c.scale;
  s.offset = c.offset;
  return s;
}

double ExtractCanSignal(const CompiledCanSignal& s, const CanFrame& frame) {
  const uint64_t word =
      s.motorola ? bytes::ReadU64Be(frame.data.data()) : bytes::ReadU64Le(frame.data.data());
  const uint64_t mask = s.length_bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << s.length_bits) - 1;
  // Bytes past the DLC are ignored even if a caller left garbage there: the field lies
  // within min_dlc bytes, which Decode() checked, so only the masked bits matter.
  uint64_t raw = (word >> s.shift) & mask;
  double value = 0.0;
  if (s.is_signed) {
    if (s.length_bits < 64 && ((raw >> (s.length_bits - 1)) & 1u) != 0) raw |= ~mask;
    value = static_cast<double>(static_cast<int64_t>(raw));
  } else {
    value = static_cast<double>(raw);
  }
  return value * s.scale + s.offset;
}

std::optional<WheelOdomDecoder> WheelOdomDecoder::Create(const CanConfig& config,
                                                         ConfigIssues* issues) {
  ConfigIssues found = config.ValidateLayout();
  if (!found.empty()) {
    if (issues != nullptr) *issues = std::move(found);
    return std::nullopt;
  }
  WheelOdomDecoder d;
  d.wheel_speeds_ = config.mode == "wheel_speeds";
  d.speed_factor_ = config.wheel_speed_unit == "radps" ? config.wheel_radius_m : 1.0;
  d.track_width_m_ = config.track_width_m;
  d.max_pair_skew_ns_ = SecToNs(config.max_pair_skew_s);
  for (const auto& sc : config.signals) {
    const bool first = sc.role == "left_wheel_speed" || sc.role == "linear_velocity";
    d.signals_[first ? 0 : 1] = *CompileCanSignal(sc);
  }
  d.ids_[0] = 0;
  d.num_ids_ = 1;
  const auto& a = d.signals_[0];
  const auto& b = d.signals_[1];
  if (a.id != b.id || a.extended != b.extended) {
    d.ids_[1] = 1;
    d.num_ids_ = 2;
  }
  return d;
}

std::optional<WheelOdomSample> WheelOdomDecoder::Decode(const CanFrame& frame, int64_t t_ns) {
  ++counters_.frames;
  std::array<bool, 2> match{};
  for (size_t k = 0; k < signals_.size(); ++k) {
    const CompiledCanSignal& s = signals_[k];
    match[k] = !frame.error && s.id == frame.id && s.extended == frame.extended;
  }
  if (frame.error || ((match[0] || match[1]) && frame.remote)) {
    ++counters_.remote_or_error;
    return std::nullopt;
  }
  if (!match[0] && !match[1]) {
    ++counters_.unknown_id;
    return std::nullopt;
  }
  // A frame too short for any of its signals is malformed as a whole: none of it is used.
  for (size_t k = 0; k < signals_.size(); ++k) {
    const CompiledCanSignal& s = signals_[k];
    if (match[k] && (frame.dlc > 8 || frame.dlc < s.min_dlc ||
                     (s.exact_dlc != 0 && frame.dlc != s.exact_dlc))) {
      ++counters_.bad_dlc;
      return std::nullopt;
    }
  }
  for (size_t k = 0; k < signals_.size(); ++k) {
    if (!match[k]) continue;
    if (fresh_[k]) ++counters_.unpaired_dropped;  // the partner never came
    value_[k] = ExtractCanSignal(signals_[k], frame);
    value_t_ns_[k] = t_ns;
    fresh_[k] = true;
  }
  ++counters_.frames_used;
  return MakeSample(t_ns);
}

std::optional<WheelOdomSample> WheelOdomDecoder::MakeSample(int64_t t_ns) {
  if (!fresh_[0] || !fresh_[1]) return std::nullopt;
  const int64_t skew_ns = value_t_ns_[0] - value_t_ns_[1];
  if (std::llabs(skew_ns) > max_pair_skew_ns_) {
    fresh_[skew_ns < 0 ? 0 : 1] = false;  // keep the newer value, wait for a new partner
    ++counters_.unpaired_dropped;
    return std::nullopt;
  }
  fresh_ = {false, false};
  WheelOdomSample out;
  out.t_ns = t_ns;
  if (wheel_speeds_) {
    out.has_wheel_speeds = true;
    out.left_wheel_mps = value_[0] * speed_factor_;
    out.right_wheel_mps = value_[1] * speed_factor_;
    out.linear_velocity_mps = 0.5 * (out.right_wheel_mps + out.left_wheel_mps);
    out.yaw_rate_radps = (out.right_wheel_mps - out.left_wheel_mps) / track_width_m_;
  } else {
    out.linear_velocity_mps = value_[0];
    out.yaw_rate_radps = value_[1];
  }
  ++counters_.samples;
  return out;
}

}  // namespace swlio::drivers

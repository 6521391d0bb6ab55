#include "swlio/drivers/can_config.h"

#include <net/if.h>

#include <cmath>

namespace swlio::drivers {
namespace {

constexpr int64_t kMaxStandardId = 0x7FF;
constexpr int64_t kMaxExtendedId = 0x1FFFFFFF;

/// Bits the field spans past its first bit in the 64-bit frame payload, or -1 when the
/// start is invalid. Intel fields grow towards higher bit numbers; Motorola fields grow from
/// the MSB towards later bytes (big-endian bit order: byte 0 bit 7 first).
int64_t LastBitIndex(const CanSignalConfig& s, int64_t start) {
  if (start < 0 || start > 63) return -1;
  if (s.byte_order == "motorola") {
    const int64_t msb_linear = (start / 8) * 8 + (7 - start % 8);
    return msb_linear + s.length_bits - 1;
  }
  return start + s.length_bits - 1;
}

}  // namespace

ConfigIssues CanSignalConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues,
            role == "left_wheel_speed" || role == "right_wheel_speed" ||
                role == "linear_velocity" || role == "angular_velocity",
            "role",
            "must be left_wheel_speed, right_wheel_speed, linear_velocity or angular_velocity, "
            "got '" +
                role + "'");
  CheckInRange<int64_t>(issues, "can_id", can_id, 0, extended ? kMaxExtendedId : kMaxStandardId);
  CheckThat(issues, byte_order == "intel" || byte_order == "motorola", "byte_order",
            "must be intel or motorola, got '" + byte_order + "'");
  CheckInRange<int64_t>(issues, "length_bits", length_bits, 1, 64);
  CheckThat(issues, (start_bit >= 0) != (byte_offset >= 0), "start_bit",
            "give exactly one of start_bit and byte_offset");
  if (start_bit >= 0) CheckInRange<int64_t>(issues, "start_bit", start_bit, 0, 63);
  if (byte_offset >= 0) CheckInRange<int64_t>(issues, "byte_offset", byte_offset, 0, 7);
  CheckThat(issues, std::isfinite(scale) && scale != 0.0, "scale", "must be finite and non-zero");
  CheckThat(issues, std::isfinite(offset), "offset", "must be finite");
  CheckInRange<int64_t>(issues, "dlc", dlc, 0, 8);
  if (!issues.empty()) return issues;

  const int64_t start = start_bit >= 0
                            ? start_bit
                            : (byte_order == "motorola" ? byte_offset * 8 + 7 : byte_offset * 8);
  const int64_t last = LastBitIndex(*this, start);
  CheckThat(issues, last >= 0 && last <= 63, "length_bits",
            "the field runs past the 8 data bytes of a classic CAN frame");
  if (dlc > 0 && last >= 0) {
    CheckThat(issues, last / 8 < dlc, "dlc", "the field runs past the required data length");
  }
  return issues;
}

ConfigIssues CanConfig::ValidateLayout() const {
  ConfigIssues issues;
  CheckThat(issues, mode == "wheel_speeds" || mode == "twist", "mode",
            "must be wheel_speeds or twist, got '" + mode + "'");
  CheckThat(issues, wheel_speed_unit == "mps" || wheel_speed_unit == "radps", "wheel_speed_unit",
            "must be mps or radps, got '" + wheel_speed_unit + "'");
  CheckPositive(issues, "wheel_radius_m", wheel_radius_m);
  CheckPositive(issues, "track_width_m", track_width_m);
  CheckInRange(issues, "max_pair_skew_s", max_pair_skew_s, 0.0, 10.0);
  for (size_t i = 0; i < signals.size(); ++i) {
    AppendWithPrefix(issues, "signals[" + std::to_string(i) + "]", signals[i].Validate());
  }
  const bool wheels = mode == "wheel_speeds";
  const char* first = wheels ? "left_wheel_speed" : "linear_velocity";
  const char* second = wheels ? "right_wheel_speed" : "angular_velocity";
  int n_first = 0;
  int n_second = 0;
  for (const auto& s : signals) {
    n_first += s.role == first ? 1 : 0;
    n_second += s.role == second ? 1 : 0;
  }
  CheckThat(issues, n_first == 1 && n_second == 1 && signals.size() == 2, "signals",
            "mode " + mode + " needs exactly one " + first + " and one " + second + " signal");
  return issues;
}

ConfigIssues CanConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues, !interface.empty() && interface.size() < IFNAMSIZ, "interface",
            "must be an interface name of 1 to " + std::to_string(IFNAMSIZ - 1) + " characters");
  if (enabled || !signals.empty()) {
    const ConfigIssues layout = ValidateLayout();
    issues.insert(issues.end(), layout.begin(), layout.end());
  }
  return issues;
}

}  // namespace swlio::drivers

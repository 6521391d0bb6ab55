#pragma once
/// @file
/// The field's disturbances the simulator can add to any scenario (issue 36): which are on, by
/// name, as `swlio-sim --disturb LIST` takes them. Each model lives with the sensor it acts on
/// and documents its magnitudes and their sources; ApplyDisturbances (apply_disturbances.h)
/// turns the set on in a SimSetup.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace swlio::sim {

enum class Disturbance : uint8_t {
  kPeople,       ///< maintenance crews walking through the bays
  kVehicles,     ///< vehicles driving, stopping, parked for a while then leaving
  kVibration,    ///< chassis vibration (motors and terrain) on the IMU and the LiDAR's pose
  kMixedPixels,  ///< returns between two surfaces at depth discontinuities
  kRain,         ///< spurious near returns from rain drops
  kDust,         ///< spurious near returns from dust
  kDropouts,     ///< beams lost on dark or wet surfaces
  kTimeOffset,   ///< an unknown constant LiDAR–IMU time offset on top of the clock model's
  kTemperature,  ///< IMU bias drift with the device's temperature
};

/// Every disturbance, in the order above.
std::vector<Disturbance> AllDisturbances();

/// Its name on the command line and in manifests: people, vehicles, vibration, mixed_pixels,
/// rain, dust, dropouts, time_offset, temperature.
const char* DisturbanceName(Disturbance d);

class DisturbanceSet {
 public:
  bool Has(Disturbance d) const { return (bits_ >> static_cast<unsigned>(d)) & 1u; }
  void Add(Disturbance d) { bits_ |= 1u << static_cast<unsigned>(d); }
  void Add(const DisturbanceSet& other) { bits_ |= other.bits_; }
  bool Empty() const { return bits_ == 0; }
  /// Comma-separated names in the enum's order; "none" when empty.
  std::string ToString() const;

 private:
  uint32_t bits_ = 0;
};

/// "people,vibration", "all" or "none" (names as DisturbanceName). Nothing, with `error` set,
/// for an unknown or empty name.
std::optional<DisturbanceSet> ParseDisturbanceList(const std::string& list, std::string* error);

}  // namespace swlio::sim

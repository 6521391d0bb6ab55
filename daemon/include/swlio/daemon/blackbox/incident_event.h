#pragma once
/// @file
/// A moment a field engineer will ask about: what opens or joins an incident.

#include <cstdint>
#include <string>

namespace swlio::daemon {

struct IncidentEvent {
  int64_t t_ns = 0;         ///< daemon time
  int64_t realtime_ns = 0;  ///< CLOCK_REALTIME then (names the incident)
  std::string reason;       ///< divergence, lidar_silent, ... (docs/blackbox.md)
  std::string detail;       ///< one line for people
};

}  // namespace swlio::daemon

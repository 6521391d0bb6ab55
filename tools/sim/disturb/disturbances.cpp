#include "disturb/disturbances.h"

#include <sstream>

namespace swlio::sim {

std::vector<Disturbance> AllDisturbances() {
  return {Disturbance::kPeople,      Disturbance::kVehicles,   Disturbance::kVibration,
          Disturbance::kMixedPixels, Disturbance::kRain,       Disturbance::kDust,
          Disturbance::kDropouts,    Disturbance::kTimeOffset, Disturbance::kTemperature};
}

const char* DisturbanceName(Disturbance d) {
  switch (d) {
    case Disturbance::kPeople:
      return "people";
    case Disturbance::kVehicles:
      return "vehicles";
    case Disturbance::kVibration:
      return "vibration";
    case Disturbance::kMixedPixels:
      return "mixed_pixels";
    case Disturbance::kRain:
      return "rain";
    case Disturbance::kDust:
      return "dust";
    case Disturbance::kDropouts:
      return "dropouts";
    case Disturbance::kTimeOffset:
      return "time_offset";
    case Disturbance::kTemperature:
      return "temperature";
  }
  return "?";
}

std::string DisturbanceSet::ToString() const {
  std::string out;
  for (Disturbance d : AllDisturbances()) {
    if (!Has(d)) continue;
    if (!out.empty()) out += ',';
    out += DisturbanceName(d);
  }
  return out.empty() ? "none" : out;
}

std::optional<DisturbanceSet> ParseDisturbanceList(const std::string& list, std::string* error) {
  DisturbanceSet set;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (name == "none") continue;
    if (name == "all") {
      for (Disturbance d : AllDisturbances()) set.Add(d);
      continue;
    }
    bool known = false;
    for (Disturbance d : AllDisturbances()) {
      if (name == DisturbanceName(d)) {
        set.Add(d);
        known = true;
      }
    }
    if (!known) {
      if (error != nullptr) {
        std::string& e = *error;
        e = "unknown disturbance '";
        e += name;
        e += "' (known:";
        for (Disturbance d : AllDisturbances()) (e += ' ') += DisturbanceName(d);
        e += ", all, none)";
      }
      return std::nullopt;
    }
  }
  return set;
}

}  // namespace swlio::sim

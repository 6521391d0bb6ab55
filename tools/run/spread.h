#pragma once
/// @file
/// {median, p99, max} of a sample of timings (nearest rank), for swlio-run's summary lines.

#include <algorithm>
#include <array>
#include <vector>

namespace swlio::tools {

/// {median, p99, max} of `v` (zeros when empty).
inline std::array<double, 3> Spread(std::vector<double> v) {
  if (v.empty()) return {0.0, 0.0, 0.0};
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) {
    return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
  };
  return {at(0.5), at(0.99), v.back()};
}

}  // namespace swlio::tools

#pragma once
/// @file
/// Numbers written to files that other programs read (recording manifests): the shortest
/// decimal text that reads back as the same double, so that nothing is lost on the way
/// (a LiDAR clock offset of 1700081385.407 s must not become 1700081385).

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

namespace swlio {

/// The shortest text that std::from_chars, strtod or Python's float() read back as exactly `v`
/// (std::to_chars), always with a '.' in its significand ("600.0", "1.0e-05") so that YAML 1.1
/// readers take it as a float too. Non-finite values give "nan", "inf" or "-inf".
inline std::string ExactNumber(double v) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  std::string text(buffer.data(), ec == std::errc() ? end : buffer.data());
  if (!std::isfinite(v) || text.find('.') != std::string::npos) return text;
  const size_t exponent = text.find('e');
  text.insert(exponent == std::string::npos ? text.size() : exponent, ".0");
  return text;
}

}  // namespace swlio

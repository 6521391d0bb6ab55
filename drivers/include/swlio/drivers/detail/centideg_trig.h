#pragma once
/// @file
/// Sine and cosine of whole hundredths of a degree, the angle unit of RoboSense and Velodyne
/// packets (azimuths are 0–35999 in 0.01°). Shared by the LiDAR decoders so that a packet costs
/// table look-ups, not libm calls. Built once on first use, in static storage (no heap).

#include <array>
#include <cstddef>
#include <cstdint>

namespace swlio::drivers::detail {

class CentidegTrig {
 public:
  static constexpr int32_t kSteps = 36000;  ///< one turn in 0.01° steps

  /// The process-wide table (thread-safe initialization on first call).
  static const CentidegTrig& Get();

  /// Wraps any integer angle in 0.01° into [0, 36000).
  static constexpr int32_t Wrap(int32_t cdeg) {
    const int32_t r = cdeg % kSteps;
    return r < 0 ? r + kSteps : r;
  }
  float Sin(int32_t cdeg) const { return sin_[static_cast<size_t>(Wrap(cdeg))]; }
  float Cos(int32_t cdeg) const { return cos_[static_cast<size_t>(Wrap(cdeg))]; }

 private:
  CentidegTrig();
  std::array<float, kSteps> sin_{};
  std::array<float, kSteps> cos_{};
};

}  // namespace swlio::drivers::detail

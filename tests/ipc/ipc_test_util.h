#pragma once
/// @file
/// Helpers for the ipc tests: loopback configurations on distinct domains, waiting for
/// discovery, bit-exact comparisons and reproducible awkward values.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <thread>

#include "swlio/ipc/ipc_config.h"
#include "swlio/ipc/messages.h"
#include "test_data.h"

namespace swlio::ipc::test_util {

/// Every test participant loads the shipped loopback XML. Each test uses its own domain id so
/// that tests running in parallel never see each other.
inline IpcConfig LoopbackConfig(int64_t domain) {
  IpcConfig config;
  config.domain_id = domain;
  config.dds_config_file = (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string();
  return config;
}

/// Polls `done` every millisecond until it holds or `timeout_s` passes.
template <typename Predicate>
bool WaitFor(Predicate done, double timeout_s = 15.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

inline uint64_t Bits(double v) {
  uint64_t b = 0;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

inline double FromBits(uint64_t b) {
  double v = 0.0;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

/// Doubles that a lossy path would change: signed zero, subnormal, NaN with payload, infinities,
/// and values with all 53 mantissa bits in use.
inline double Awkward(int i) {
  switch (i % 8) {
    case 0:
      return -0.0;
    case 1:
      return std::numeric_limits<double>::denorm_min() * (i + 1);
    case 2:
      return FromBits(0x7ff800000000beefULL);  // quiet NaN with a payload
    case 3:
      return -std::numeric_limits<double>::infinity();
    case 4:
      return 1.0 / 3.0 + i;
    case 5:
      return -std::nextafter(1e300, 0.0);
    case 6:
      return std::numeric_limits<double>::max();
    default:
      return std::sqrt(2.0) * (i - 17);
  }
}

/// Bit-exact equality of double arrays (NaN payloads and -0.0 included).
template <size_t N>
::testing::AssertionResult SameBits(const std::array<double, N>& a,
                                    const std::array<double, N>& b) {
  for (size_t i = 0; i < N; ++i) {
    if (Bits(a[i]) != Bits(b[i])) {
      return ::testing::AssertionFailure()
             << "element " << i << ": " << std::hexfloat << a[i] << " vs " << b[i];
    }
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult SamePose(const Pose& a, const Pose& b) {
  auto r = SameBits(a.position_m, b.position_m);
  return r ? SameBits(a.orientation_xyzw, b.orientation_xyzw) : r;
}

/// A pose sample with every double awkward and distinct per `seed`.
inline PoseWithCovarianceStamped MakePose(int seed, int64_t t_ns) {
  PoseWithCovarianceStamped p;
  p.t_ns = t_ns;
  p.frame_id = "map";
  p.pose.position_m = {Awkward(seed), 1.0e6 + seed, Awkward(seed + 4)};
  p.pose.orientation_xyzw = {0.5, -0.5, Awkward(seed + 7), std::sqrt(0.5) + seed};
  for (size_t i = 0; i < p.covariance.size(); ++i) p.covariance[i] = Awkward(seed + int(i));
  return p;
}

}  // namespace swlio::ipc::test_util

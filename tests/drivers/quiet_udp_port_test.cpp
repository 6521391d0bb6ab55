// The tests' own UDP ports (tests/support/udp_port.h): outside the DDS bands, and drawn evenly,
// so that test processes running side by side seldom pick the same one.

#include <gtest/gtest.h>

#include <set>

#include "udp_port.h"

namespace swlio::test {
namespace {

constexpr int kDdsBase = 7400;  // RTPS port mapping: domain d's band starts at 7400 + 250·d
constexpr int kDdsGain = 250;
constexpr int kDdsBand = 150;

TEST(QuietUdpPort, DrawsEvenlyFromThePortsOutsideTheDdsBands) {
  constexpr int kDraws = 500;
  std::set<int> ports;
  int just_above_a_band = 0;
  for (int i = 0; i < kDraws; ++i) {
    const int port = QuietUdpPort();
    ASSERT_GE(port, 10'000);
    ASSERT_GE((port - kDdsBase) % kDdsGain, kDdsBand) << port << " is in a DDS band";
    ports.insert(port);
    if ((port - kDdsBase) % kDdsGain == kDdsBand) ++just_above_a_band;
  }
  EXPECT_EQ(ports.size(), static_cast<size_t>(kDraws));
  // One port in 100 of those allowed is the first above a band: 5 expected in 500 draws
  // (P(over 20) < 1e-6). Drawing a start among all ports and walking up to an allowed one sent
  // the 60 % that start in a band there, about 90 of these in 500 draws.
  EXPECT_LE(just_above_a_band, 20);
}

}  // namespace
}  // namespace swlio::test

#include "swlio/core/time.h"

#include <gtest/gtest.h>

namespace swlio {
namespace {

TEST(Time, SecondsAndNanosecondsRoundTrip) {
  EXPECT_EQ(SecToNs(1.5), 1'500'000'000);
  EXPECT_EQ(SecToNs(-0.25), -250'000'000);
  EXPECT_EQ(SecToNs(1e-9 * 0.6), 1);  // rounds to nearest
  EXPECT_DOUBLE_EQ(NsToSec(2'500'000'000), 2.5);
  // 2026 in ns since the epoch survives the round trip to within 1 µs (double precision).
  constexpr int64_t t = 1'795'000'000'123'456'789;
  EXPECT_LE(std::llabs(SecToNs(NsToSec(t)) - t), 1000);
}

}  // namespace
}  // namespace swlio

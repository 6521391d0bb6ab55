#include "swlio/daemon/pipeline/sweep_shedding.h"

#include <gtest/gtest.h>

namespace swlio::daemon {
namespace {

constexpr int64_t kMaxLagNs = 500'000'000;

TEST(SweepShedding, TakesEverySweepWhileOnTime) {
  SweepShedding s(kMaxLagNs);
  for (int i = 0; i < 100; ++i) EXPECT_TRUE(s.Take(kMaxLagNs));  // at the limit: on time
  EXPECT_EQ(s.skipped(), 0u);
}

TEST(SweepShedding, SkipsEveryOtherSweepWhileBehind) {
  SweepShedding s(kMaxLagNs);
  int taken = 0;
  for (int i = 0; i < 10; ++i) taken += s.Take(kMaxLagNs + 1) ? 1 : 0;
  EXPECT_EQ(taken, 5);
  EXPECT_EQ(s.skipped(), 5u);
  // Caught up: every sweep again.
  for (int i = 0; i < 10; ++i) EXPECT_TRUE(s.Take(0));
  EXPECT_EQ(s.skipped(), 5u);
}

TEST(SweepShedding, NeverSkipsTwoInARow) {
  SweepShedding s(kMaxLagNs);
  bool previous_taken = true;
  for (int i = 0; i < 50; ++i) {
    const bool taken = s.Take(i % 3 == 0 ? 0 : 10 * kMaxLagNs);
    EXPECT_TRUE(taken || previous_taken) << "sweep " << i;
    previous_taken = taken;
  }
  EXPECT_GT(s.skipped(), 0u);
}

TEST(SweepShedding, ZeroLimitNeverSkips) {
  SweepShedding s(0);
  for (int i = 0; i < 10; ++i) EXPECT_TRUE(s.Take(int64_t{1} << 40));
  EXPECT_EQ(s.skipped(), 0u);
}

}  // namespace
}  // namespace swlio::daemon

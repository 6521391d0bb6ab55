#include "swlio/daemon/pipeline/sweep_shedding.h"

#include <gtest/gtest.h>

#include <algorithm>

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

TEST(SweepShedding, SkipsNoTwoInARowWithinTwiceTheLimit) {
  SweepShedding s(kMaxLagNs);
  bool previous_taken = true;
  for (int i = 0; i < 50; ++i) {
    const bool taken = s.Take(i % 3 == 0 ? 0 : 2 * kMaxLagNs);
    EXPECT_TRUE(taken || previous_taken) << "sweep " << i;
    previous_taken = taken;
  }
  EXPECT_GT(s.skipped(), 0u);
}

// Further behind, longer runs are skipped (one more per limit of lag), never more than kMaxRun:
// the estimator's load falls to a fifth while the CPU does not suffice.
TEST(SweepShedding, SkipsLongerRunsTheFurtherBehindUpToTheMaximum) {
  const auto longest_run = [](int64_t lag_ns) {
    SweepShedding s(kMaxLagNs);
    int run = 0, longest = 0;
    for (int i = 0; i < 40; ++i) {
      run = s.Take(lag_ns) ? 0 : run + 1;
      longest = std::max(longest, run);
    }
    return longest;
  };
  EXPECT_EQ(longest_run(kMaxLagNs + 1), 1);
  EXPECT_EQ(longest_run(3 * kMaxLagNs), 2);
  EXPECT_EQ(longest_run(3 * kMaxLagNs + 1), 3);
  EXPECT_EQ(longest_run(100 * kMaxLagNs), SweepShedding::kMaxRun);
}

TEST(SweepShedding, ZeroLimitNeverSkips) {
  SweepShedding s(0);
  for (int i = 0; i < 10; ++i) EXPECT_TRUE(s.Take(int64_t{1} << 40));
  EXPECT_EQ(s.skipped(), 0u);
}

}  // namespace
}  // namespace swlio::daemon

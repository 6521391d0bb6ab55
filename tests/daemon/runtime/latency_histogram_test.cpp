// LatencyHistogram: log-spaced bins, quantiles of the interval between two snapshots.

#include "swlio/daemon/runtime/latency_histogram.h"

#include <gtest/gtest.h>

namespace swlio::daemon {
namespace {

TEST(LatencyHistogram, BinsAreUpperBoundsWithinAQuarterOctave) {
  for (const int64_t ns :
       {int64_t{0}, int64_t{30'000}, int64_t{1'000'000}, int64_t{2'500'000'000}}) {
    const int bin = LatencyHistogram::Bin(ns);
    EXPECT_GE(LatencyHistogram::UpperEdgeNs(bin), ns) << ns;
    if (bin > 0) {
      EXPECT_LT(LatencyHistogram::UpperEdgeNs(bin - 1), ns) << ns;
    }
    EXPECT_LE(static_cast<double>(LatencyHistogram::UpperEdgeNs(bin)),
              1.19 * static_cast<double>(ns) + 25000.0);
  }
  EXPECT_EQ(LatencyHistogram::Bin(int64_t{3600} * 1'000'000'000), LatencyHistogram::kBins - 1);
  EXPECT_EQ(LatencyHistogram::Bin(-5), 0);
}

TEST(LatencyHistogram, QuantilesOfTheIntervalOnly) {
  LatencyHistogram h;
  for (int i = 0; i < 1000; ++i) h.Add(500'000'000);  // an earlier interval: 500 ms each
  const LatencyHistogram::Counts before = h.Snapshot();
  for (int i = 0; i < 990; ++i) h.Add(1'000'000);  // then 99 % at 1 ms, 1 % at 40 ms
  for (int i = 0; i < 10; ++i) h.Add(40'000'000);
  const LatencySummary s = Summarize(h.Snapshot(), before);
  EXPECT_EQ(s.count, 1000u);
  EXPECT_GE(s.p50_ms, 1.0);
  EXPECT_LT(s.p50_ms, 1.2);
  EXPECT_LT(s.p99_ms, 1.2) << "the 990th of 1000 is still 1 ms";
  EXPECT_GE(s.max_ms, 40.0);
  EXPECT_LT(s.max_ms, 48.0);
  const LatencySummary all = Summarize(h.Snapshot(), LatencyHistogram::Counts{});
  EXPECT_GE(all.max_ms, 500.0);
  EXPECT_EQ(Summarize(before, before).count, 0u);
}

}  // namespace
}  // namespace swlio::daemon

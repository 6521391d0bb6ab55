// swlio-echo's --latency-summary: one row per topic and interval, with the interval's count
// and percentiles; empty intervals write nothing; Flush writes the interval in progress.

#include "latency_summary.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "swlio/core/time.h"

namespace swlio::tools::echo {
namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(LatencySummary, OneRowPerTopicAndIntervalWithItsPercentiles) {
  std::ostringstream out;
  LatencySummary summary(&out, 1.0);
  const int64_t t0 = 50 * kNsPerSec;
  // First second: 100 poses aged 1..100 ms, delivered in 10..1000 µs; one odometry.
  for (int i = 1; i <= 100; ++i) {
    summary.Add(ipc::Topic::kPose, t0 + i * 5 * kNsPerMs, i * 10'000, i * kNsPerMs);
  }
  summary.Add(ipc::Topic::kOdometry, t0 + 900 * kNsPerMs, 2'000, 20 * kNsPerMs);
  // Nothing for two seconds, then one pose in the fourth.
  summary.Add(ipc::Topic::kPose, t0 + 3'500 * kNsPerMs, 5'000, 3 * kNsPerMs);
  summary.Flush();
  const auto lines = Lines(out.str());
  ASSERT_EQ(lines.size(), 4u) << out.str();
  EXPECT_EQ(lines[0], kLatencySummaryHeader);
  EXPECT_EQ(lines[1], "1.000,pose,100,510.0,990.0,1000.0,51.000,99.000,100.000");
  EXPECT_EQ(lines[2], "1.000,odometry,1,2.0,2.0,2.0,20.000,20.000,20.000");
  EXPECT_EQ(lines[3], "3.495,pose,1,5.0,5.0,5.0,3.000,3.000,3.000");
}

TEST(LatencySummary, NothingReceivedWritesOnlyTheHeader) {
  std::ostringstream out;
  LatencySummary summary(&out, 10.0);
  summary.Flush();
  const auto lines = Lines(out.str());
  ASSERT_EQ(lines.size(), 1u) << out.str();
  EXPECT_EQ(lines[0], kLatencySummaryHeader);
}

}  // namespace
}  // namespace swlio::tools::echo

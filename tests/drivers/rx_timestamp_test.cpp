#include "swlio/drivers/rx_timestamp.h"

#include <gtest/gtest.h>

#include "swlio/core/time.h"

namespace swlio::drivers {
namespace {

timespec RealtimeNow() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return ts;
}

timespec Shift(timespec ts, int64_t ns) {
  const int64_t total = static_cast<int64_t>(ts.tv_sec) * kNsPerSec + ts.tv_nsec + ns;
  return {static_cast<time_t>(total / kNsPerSec), static_cast<long>(total % kNsPerSec)};
}

TEST(RealtimeToMonotonic, MapsARecentRealtimeStampToMonotonicTime) {
  const timespec stamp = Shift(RealtimeNow(), -2 * kNsPerMs);  // "received" 2 ms ago
  const int64_t mono_now = MonotonicNowNs();
  const RealtimeToMonotonic clock = RealtimeToMonotonic::Measure();
  const std::optional<int64_t> t = clock.Convert(stamp);
  ASSERT_TRUE(t);
  EXPECT_NEAR(static_cast<double>(*t), static_cast<double>(mono_now - 2 * kNsPerMs), 1e6);
  EXPECT_LE(*t, clock.read_mono_ns);
}

TEST(RealtimeToMonotonic, RejectsImplausibleStamps) {
  const RealtimeToMonotonic clock = RealtimeToMonotonic::Measure();
  const timespec now = RealtimeNow();
  EXPECT_FALSE(clock.Convert(Shift(now, 50 * kNsPerMs)));                // in the future
  EXPECT_FALSE(clock.Convert(Shift(now, -kMaxStampAgeNs - kNsPerSec)));  // far too old
  EXPECT_FALSE(clock.Convert(timespec{0, 0}));                           // no stamp
  EXPECT_TRUE(clock.Convert(Shift(now, -kMaxStampAgeNs + kNsPerSec)));
}

TEST(RealtimeToMonotonic, KeepsTheTightestReadingOfTheClocks) {
  // Realtime is monotonic + 1 s here. The first reading was preempted for 400 µs right after
  // its first monotonic read: its midpoint puts the offset 200 µs off. The second is tighter,
  // the third tighter still but over the search's limit of readings.
  const ClockReading readings[] = {{1'000'000, 1'001'000'100, 1'400'000},
                                   {2'000'000, 1'002'000'500, 2'001'000},
                                   {3'000'000, 1'003'000'000, 3'000'010}};
  int calls = 0;
  const auto read = [&] { return readings[calls++]; };
  const ClockReading best = TightestClockReading(read, 2, 100);
  EXPECT_EQ(calls, 2);
  const RealtimeToMonotonic clock = RealtimeToMonotonic::FromReading(best);
  EXPECT_EQ(clock.offset_ns, -kNsPerSec);
  EXPECT_EQ(clock.read_mono_ns, 2'001'000);
  EXPECT_EQ(RealtimeToMonotonic::FromReading(readings[0]).offset_ns, -kNsPerSec + 199'900);
}

TEST(RealtimeToMonotonic, StopsAtATightReading) {
  const ClockReading readings[] = {{0, 1'000'000'400, 800}, {5'000, 1'000'005'000, 5'000}};
  int calls = 0;
  const auto read = [&] { return readings[calls++]; };
  const ClockReading best = TightestClockReading(read, kClockReadTries, kTightClockReadNs);
  EXPECT_EQ(calls, 1);  // 800 ns between the monotonic reads: no second reading
  EXPECT_EQ(best.mono_mid_ns(), 400);
}

}  // namespace
}  // namespace swlio::drivers

// Stamps in ROS time: the daemon's monotonic time plus the tracked realtime − monotonic offset;
// a slew followed without a step, a step of the wall clock (either way) followed, counted and
// returned; monotonic mode the identity. The clocks are injected: the wall clock cannot be
// stepped in a test (time namespaces do not virtualize CLOCK_REALTIME).

#include "swlio/daemon/output/stamp_clock.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "swlio/daemon/runtime/watchdog.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kSec = 1'000'000'000;
constexpr int64_t kMs = 1'000'000;

/// Two hand-driven clocks: monotonic since "boot", realtime in 2026.
struct FakeClocks {
  int64_t monotonic_ns = 100 * kSec;
  int64_t realtime_ns = 1'780'000'000 * kSec + 123'456'789;

  ClockSources Sources() {
    return {[this] { return monotonic_ns; }, [this] { return realtime_ns; }};
  }
  /// Both advance by dt; the wall clock at (1 + slew) its rate.
  void Advance(int64_t dt_ns, double slew = 0.0) {
    monotonic_ns += dt_ns;
    realtime_ns += dt_ns + std::llround(static_cast<double>(dt_ns) * slew);
  }
  int64_t Offset() const { return realtime_ns - monotonic_ns; }
};

TEST(StampClock, RealtimeStampsAreMonotonicTimePlusTheOffset) {
  FakeClocks clocks;
  const StampClock stamps(/*realtime=*/true, clocks.Sources());
  EXPECT_EQ(stamps.offset_ns(), clocks.Offset());
  EXPECT_EQ(stamps.ToStamp(100 * kSec), clocks.realtime_ns);
  EXPECT_EQ(stamps.ToStamp(99 * kSec + 7), clocks.realtime_ns - kSec + 7);
  EXPECT_TRUE(stamps.counters().realtime);
  EXPECT_EQ(stamps.counters().steps, 0u);
}

TEST(StampClock, MonotonicModeKeepsTheStampsEvenAcrossAStep) {
  FakeClocks clocks;
  StampClock stamps(/*realtime=*/false, clocks.Sources());
  EXPECT_EQ(stamps.ToStamp(123'456'789), 123'456'789);
  clocks.Advance(10 * kMs);
  clocks.realtime_ns += 10 * kSec;
  EXPECT_TRUE(stamps.Update().has_value()) << "the offset is tracked in both modes";
  EXPECT_EQ(stamps.ToStamp(123'456'789), 123'456'789);
  EXPECT_FALSE(stamps.counters().realtime);
  EXPECT_EQ(stamps.counters().steps, 1u);
}

// NTP's 500 ppm for 100 s (50 ms in all), then chrony's fastest slew (83,333 ppm) for 1 s:
// followed sample by sample, never a step.
TEST(StampClock, ASlewIsFollowedButIsNoStep) {
  FakeClocks clocks;
  StampClock stamps(true, clocks.Sources());
  const int64_t start_offset = clocks.Offset();
  for (int i = 0; i < 10'000; ++i) {
    clocks.Advance(10 * kMs, 500e-6);
    ASSERT_FALSE(stamps.Update().has_value()) << "sample " << i;
  }
  EXPECT_EQ(clocks.Offset() - start_offset, 50 * kMs);
  for (int i = 0; i < 50; ++i) {
    clocks.Advance(20 * kMs, 83'333e-6);  // the publisher's longest sleep between samples
    ASSERT_FALSE(stamps.Update().has_value()) << "fast slew, sample " << i;
  }
  EXPECT_EQ(stamps.offset_ns(), clocks.Offset());
  EXPECT_EQ(stamps.ToStamp(clocks.monotonic_ns), clocks.realtime_ns);
  EXPECT_EQ(stamps.counters().steps, 0u);
}

TEST(StampClock, ATenSecondStepIsCountedAndTheStampsFollowIt) {
  FakeClocks clocks;
  StampClock stamps(true, clocks.Sources());
  clocks.Advance(2500 * 1000);  // one 400 Hz IMU period
  ASSERT_FALSE(stamps.Update().has_value());
  const int64_t t_ns = clocks.monotonic_ns - 3 * kMs;  // a pose from just before the step
  const int64_t before = stamps.ToStamp(t_ns);
  clocks.Advance(2500 * 1000);
  clocks.realtime_ns += 10 * kSec;  // settimeofday / chronyd makestep
  const std::optional<WallClockStep> step = stamps.Update();
  ASSERT_TRUE(step.has_value());
  EXPECT_EQ(step->step_ns, 10 * kSec);
  EXPECT_EQ(step->offset_ns, clocks.Offset());
  EXPECT_EQ(step->t_monotonic_ns, clocks.monotonic_ns);
  EXPECT_EQ(stamps.ToStamp(t_ns) - before, 10 * kSec) << "stamps follow the wall clock";
  EXPECT_EQ(stamps.ToStamp(clocks.monotonic_ns), clocks.realtime_ns);
  clocks.Advance(2500 * 1000);
  EXPECT_FALSE(stamps.Update().has_value()) << "counted once";
  const StampClockCounters c = stamps.counters();
  EXPECT_EQ(c.steps, 1u);
  EXPECT_EQ(c.last_step_ns, 10 * kSec);
  EXPECT_EQ(c.last_step_monotonic_ns, step->t_monotonic_ns);
}

TEST(StampClock, AStepBackwardsIsCountedWithItsSign) {
  FakeClocks clocks;
  StampClock stamps(true, clocks.Sources());
  clocks.Advance(5 * kMs);
  clocks.realtime_ns -= 10 * kSec;
  const std::optional<WallClockStep> step = stamps.Update();
  ASSERT_TRUE(step.has_value());
  EXPECT_EQ(step->step_ns, -10 * kSec);
  EXPECT_EQ(stamps.ToStamp(clocks.monotonic_ns), clocks.realtime_ns);
  EXPECT_EQ(stamps.counters().last_step_ns, -10 * kSec);
}

// The threshold: 1 ms plus what a 10 % slew explains over the time since the last sample.
TEST(StampClock, AStepIsAJumpBeyondOneMillisecondAndTheSlew) {
  FakeClocks clocks;
  StampClock stamps(true, clocks.Sources());
  clocks.Advance(kMs);  // up to 0.1 ms of slew
  clocks.realtime_ns += 1'050'000;
  EXPECT_FALSE(stamps.Update().has_value()) << "1.05 ms in 1 ms: within 1 ms + 10 %";
  EXPECT_EQ(stamps.ToStamp(clocks.monotonic_ns), clocks.realtime_ns) << "followed all the same";
  clocks.Advance(kMs);
  clocks.realtime_ns += 1'150'000;
  EXPECT_TRUE(stamps.Update().has_value()) << "1.15 ms in 1 ms";
  clocks.Advance(kSec);  // a publisher stalled for 1 s: 100 ms of slew is possible
  clocks.realtime_ns += 90 * kMs;
  EXPECT_FALSE(stamps.Update().has_value());
  EXPECT_EQ(stamps.counters().steps, 1u);
}

// Preempted between its reads, a pair says nothing precise: it is read again and the tightest
// pair's midpoint is used.
TEST(StampClock, APreemptedPairIsReadAgain) {
  const int64_t real = 1'780'000'000 * kSec;
  std::vector<int64_t> monotonic = {10 * kSec, 10 * kSec + 2 * kMs,  // 2 ms apart: preempted
                                    11 * kSec, 11 * kSec + 2000};    // 2 µs
  size_t next = 0;
  const ClockSources sources{[&] { return monotonic[next++]; }, [&] { return real; }};
  const ClockOffsetSample s = SampleClockOffset(sources);
  EXPECT_EQ(next, 4u) << "two pairs read";
  EXPECT_EQ(s.t_monotonic_ns, 11 * kSec + 1000);
  EXPECT_EQ(s.offset_ns, real - (11 * kSec + 1000));
}

TEST(StampClock, TheHostClocksGiveTheirOffset) {
  StampClock stamps(true);
  const int64_t offset = RealtimeNowNs() - MonotonicNowNs();
  EXPECT_NEAR(static_cast<double>(stamps.offset_ns()), static_cast<double>(offset), 1e6);
  EXPECT_GT(stamps.ToStamp(MonotonicNowNs()), 1'700'000'000 * kSec) << "a date after 2023";
}

}  // namespace
}  // namespace swlio::daemon

// ImuStage: SampleTimeFine → host time through the clock model, drops counted by cause.

#include "swlio/daemon/sensors/imu_stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace swlio::daemon {
namespace {

ImuRaw Raw(uint32_t stf, int64_t t_rx_ns) {
  ImuRaw r;
  r.t_rx_ns = t_rx_ns;
  r.sample_time_fine = stf;
  r.has_sample_time_fine = true;
  r.has_inertial = true;
  r.frame_bytes = 47;
  r.acc_mps2 = Eigen::Vector3d(0.0, 0.0, 9.8);
  r.gyro_radps = Eigen::Vector3d(0.01, 0.0, 0.0);
  return r;
}

TEST(ImuStage, MapsSampleTimeToHostWithDriftAndBursts) {
  ImuStage stage(921600);
  const int64_t host0 = 5'000'000'000;
  const double drift = 100e-6;  // the device clock runs 100 ppm fast
  const int64_t latency = static_cast<int64_t>(47 * 10 / 921600.0 * 1e9);
  double worst_ms = 0.0;
  for (int k = 0; k < 400 * 60; ++k) {  // 60 s at 400 Hz
    const int64_t true_host = host0 + int64_t{k} * 2'500'000;
    const auto stf =
        static_cast<uint32_t>(std::llround(1000.0 + static_cast<double>(k) * 25.0 * (1.0 + drift)));
    // USB-serial delivers in bursts: every 4th sample on time, the others up to 8 ms late.
    const int64_t delay = latency + (k % 4 == 0 ? 0 : 2'000'000 * (k % 4));
    const auto s = stage.Map(Raw(stf, true_host + delay));
    ASSERT_TRUE(s.has_value()) << k;
    if (k > 400 * 5) {
      worst_ms = std::max(worst_ms, std::abs(static_cast<double>(s->t_ns - true_host)) * 1e-6);
    }
  }
  EXPECT_LT(worst_ms, 0.5) << "mapped within 0.5 ms after the first windows";
  EXPECT_NEAR(stage.clock().drift_ppm, -100.0, 5.0);
  EXPECT_EQ(stage.counters().samples, 400u * 60u);
}

TEST(ImuStage, LongerFramesDoNotShiftTheTimes) {
  // Every 100th frame carries a GnssPvtData item (97 bytes more, ~1.05 ms longer on the wire),
  // the very first one too: the times of all the others must not move by that much.
  ImuStage stage(921600);
  auto tx_ns = [](int bytes) { return static_cast<int64_t>(bytes * 10 / 921600.0 * 1e9); };
  double worst_ms = 0.0;
  for (int k = 0; k < 400 * 30; ++k) {
    const int64_t true_host = 5'000'000'000 + int64_t{k} * 2'500'000;
    ImuRaw r = Raw(static_cast<uint32_t>(1000 + 25 * k), 0);
    r.frame_bytes = k % 100 == 0 ? 47 + 97 : 47;
    r.t_rx_ns = true_host + tx_ns(static_cast<int>(r.frame_bytes));
    const auto s = stage.Map(r);
    ASSERT_TRUE(s.has_value()) << k;
    if (k > 400 * 5) {
      worst_ms = std::max(worst_ms, std::abs(static_cast<double>(s->t_ns - true_host)) * 1e-6);
    }
  }
  EXPECT_LT(worst_ms, 0.2) << "a 1.05 ms bias would remain if the first frame's length held";
}

TEST(ImuStage, ABacklogOfSecondsIsNotAClockJump) {
  // A busy host: the kernel's tty worker runs late and the reader gets every sample 1.5 s late
  // for 5 s, then catches up. No byte is lost and the device clock never moved: no jump, and
  // every sample keeps its true time (mapped by the model as it stood), none dropped.
  ImuStage stage(921600);
  const int64_t latency = static_cast<int64_t>(47 * 10 / 921600.0 * 1e9);
  double worst_ms = 0.0;
  for (int k = 0; k < 400 * 40; ++k) {
    const int64_t true_host = 5'000'000'000 + int64_t{k} * 2'500'000;
    const bool behind = k >= 400 * 20 && k < 400 * 25;
    const int64_t rx = true_host + latency + (behind ? 1'500'000'000 : 0);
    const auto s = stage.Map(Raw(static_cast<uint32_t>(1000 + 25 * k), rx));
    ASSERT_TRUE(s.has_value()) << k;
    if (k > 400 * 5) {
      worst_ms = std::max(worst_ms, std::abs(static_cast<double>(s->t_ns - true_host)) * 1e-6);
    }
  }
  EXPECT_EQ(stage.clock().jumps, 0u) << "a late delivery is not a jump";
  EXPECT_LT(worst_ms, 0.5);
  EXPECT_EQ(stage.counters().out_of_order, 0u);
}

TEST(ImuStage, AStepBackBeyondAnyBacklogIsStillAJump) {
  // A device reset sets SampleTimeFine back by far more than any buffer holds (here 100 s):
  // confirmed within about a second, as before.
  ImuStage stage(921600);
  const int64_t latency = static_cast<int64_t>(47 * 10 / 921600.0 * 1e9);
  int confirmed_after = -1;
  for (int k = 0; k < 400 * 30; ++k) {
    const int64_t true_host = 5'000'000'000 + int64_t{k} * 2'500'000;
    const int64_t stf = 2'000'000 + 25 * k - (k >= 400 * 20 ? 1'000'000 : 0);  // −100 s
    stage.Map(Raw(static_cast<uint32_t>(stf), true_host + latency));
    if (confirmed_after < 0 && stage.clock().jumps > 0) confirmed_after = k - 400 * 20;
  }
  EXPECT_EQ(stage.clock().jumps, 1u);
  EXPECT_GE(confirmed_after, 0);
  EXPECT_LE(confirmed_after, 400 * 2) << "samples after the step";
}

TEST(ImuStage, DropsSamplesItCannotUse) {
  ImuStage stage(921600);
  ImuRaw no_time = Raw(1000, 1'000'000'000);
  no_time.has_sample_time_fine = false;
  EXPECT_FALSE(stage.Map(no_time));
  ImuRaw no_gyro = Raw(1025, 1'002'500'000);
  no_gyro.has_inertial = false;
  EXPECT_FALSE(stage.Map(no_gyro));
  ImuRaw nan = Raw(1050, 1'005'000'000);
  nan.acc_mps2.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(stage.Map(nan));
  EXPECT_TRUE(stage.Map(Raw(1075, 1'007'500'000)));
  EXPECT_FALSE(stage.Map(Raw(1075, 1'007'600'000))) << "a repeated sample time";
  const ImuStageCounters& c = stage.counters();
  EXPECT_EQ(c.no_sample_time, 1u);
  EXPECT_EQ(c.incomplete, 2u);
  EXPECT_EQ(c.out_of_order, 1u);
  EXPECT_EQ(c.samples, 1u);
}

}  // namespace
}  // namespace swlio::daemon

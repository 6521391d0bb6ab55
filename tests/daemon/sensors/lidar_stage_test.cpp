// LidarStage: RS16 datagrams with host receive times → sweeps on the host clock.

#include "swlio/daemon/sensors/lidar_stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "swlio/drivers/rs16_encoder.h"

namespace swlio::daemon {
namespace {

constexpr double kStepDeg = 600.0 * 6.0 * 111e-6;        // azimuth per block at 600 rpm (°)
constexpr int64_t kSensor0 = 1'700'000'000'000'000'000;  // header time of packet 0
constexpr int64_t kHost0 = 50'000'000'000;               // host time of packet 0's first firing
constexpr int64_t kPacketNs = 12 * 111'000;              // 12 blocks of 111 µs (simplified)

std::vector<uint8_t> Msop(int k) {
  drivers::Rs16MsopContent c;
  c.t_sensor_ns = kSensor0 + int64_t{k} * kPacketNs;
  c.time_format = drivers::rs16::TimeFormat::kUtc;
  for (size_t b = 0; b < 12; ++b) {
    c.blocks[b].azimuth_deg =
        std::fmod(10.0 + kStepDeg * static_cast<double>(12 * k + int(b)), 360.0);
    for (size_t s = 0; s < 32; ++s) c.blocks[b].range_m[s] = 5.0f + 0.01f * float(s);
  }
  std::vector<uint8_t> bytes(1248);
  EXPECT_TRUE(drivers::EncodeRs16Msop(c, bytes));
  return bytes;
}

TEST(LidarStage, AssemblesSweepsOnTheHostClock) {
  drivers::LidarConfig config;
  LidarStage stage(config);
  std::vector<uint8_t> difop(1248);
  drivers::Rs16DifopContent info;
  ASSERT_TRUE(drivers::EncodeRs16Difop(info, difop));
  stage.Add(difop, kHost0);
  const int packets = 75 * 5;  // five revolutions
  std::vector<HostSweep> sweeps;
  HostSweep sweep;
  for (int k = 0; k < packets; ++k) {
    // The packet leaves after its last firing (~1.32 ms) and arrives 0.2–1.2 ms later.
    const int64_t rx = kHost0 + int64_t{k} * kPacketNs + 1'323'000 + 200'000 + (k % 5) * 250'000;
    stage.Add(Msop(k), rx);
    while (stage.Pop(&sweep)) sweeps.push_back(sweep);
  }
  stage.Add(std::vector<uint8_t>(100, 0xAB), kHost0);  // neither MSOP nor DIFOP
  ASSERT_GE(sweeps.size(), 4u);
  for (size_t i = 1; i < sweeps.size(); ++i) {
    const Scan& s = sweeps[i].scan;
    EXPECT_FALSE(s.points.empty());
    EXPECT_NEAR(static_cast<double>(s.t_end_ns - s.t_start_ns) * 1e-6, 100.0, 3.0);
    // The sweep starts where the azimuth crosses 0°: (360 − 10)/kStepDeg blocks into packet 0.
    const double blocks = (360.0 * static_cast<double>(i) - 10.0) / kStepDeg;
    const double t_true_ms = static_cast<double>(kHost0) * 1e-6 + blocks * 0.111;
    EXPECT_NEAR(static_cast<double>(s.t_start_ns) * 1e-6, t_true_ms, 0.5) << "sweep " << i;
  }
  EXPECT_EQ(stage.counters().info_packets, 1u);
  EXPECT_EQ(stage.counters().bad_packets, 1u);
  EXPECT_EQ(stage.counters().data_packets, static_cast<uint64_t>(packets));
  EXPECT_TRUE(stage.clock().valid);
}

// Sweeps of a stage fed five revolutions, packet k received rx_delay_ns(k) after it left.
template <typename Delay>
std::vector<HostSweep> FiveRevolutions(LidarStage* stage, Delay rx_delay_ns) {
  std::vector<HostSweep> sweeps;
  HostSweep sweep;
  for (int k = 0; k < 75 * 5; ++k) {
    stage->Add(Msop(k), kHost0 + int64_t{k} * kPacketNs + 1'323'000 + rx_delay_ns(k));
    while (stage->Pop(&sweep)) sweeps.push_back(sweep);
  }
  return sweeps;
}

// The first two sweeps arrive 450 µs later than the rest: the lower envelope then steps down
// and maps the third sweep to start before the second ended, which the estimator would skip.
TEST(LidarStage, AClockRefitThatMapsASweepBackIsAbsorbed) {
  LidarStage stage{drivers::LidarConfig{}};
  const auto sweeps =
      FiveRevolutions(&stage, [](int k) { return 200'000 + (k < 150 ? 450'000 : 0); });
  ASSERT_GE(sweeps.size(), 4u);
  for (size_t i = 1; i < sweeps.size(); ++i) {
    EXPECT_GE(sweeps[i].scan.t_start_ns, sweeps[i - 1].scan.t_end_ns) << "sweep " << i;
    EXPECT_LT(sweeps[i].scan.t_start_ns - sweeps[i - 1].scan.t_end_ns, 1'000'000) << i;
  }
  EXPECT_GE(stage.counters().overlaps_absorbed, 1u);
}

// A step back larger than a re-fit can explain (a clock jump) is passed on unchanged.
TEST(LidarStage, ALargerStepBackIsNotHidden) {
  LidarStage stage{drivers::LidarConfig{}};
  const auto sweeps =
      FiveRevolutions(&stage, [](int k) { return 200'000 + (k < 150 ? 5'000'000 : 0); });
  ASSERT_GE(sweeps.size(), 4u);
  bool overlapped = false;
  for (size_t i = 1; i < sweeps.size(); ++i) {
    overlapped = overlapped || sweeps[i].scan.t_start_ns < sweeps[i - 1].scan.t_end_ns;
  }
  EXPECT_TRUE(overlapped);
  EXPECT_EQ(stage.counters().overlaps_absorbed, 0u);
}

// Jumps the stage's clock model counted over 10 s of packets (750/s), packet k received
// rx_delay_ns(k) after it left.
template <typename Delay>
uint64_t ClockJumpsOver10s(const drivers::LidarConfig& config, Delay rx_delay_ns) {
  LidarStage stage(config);
  HostSweep sweep;
  for (int k = 0; k < 7500; ++k) {
    stage.Add(Msop(k), kHost0 + int64_t{k} * kPacketNs + 1'323'000 + rx_delay_ns(k));
    while (stage.Pop(&sweep)) {
    }
  }
  return stage.clock().jumps;
}

// A reader starved for 2.5 s on a busy host finds the datagrams queued in its socket, 400 ms
// late: with the default 8 MiB buffer (8.7 s of RS16 datagrams) that is a backlog, not a clock
// that stepped back. A buffer of 256 KiB cannot hold 400 ms, so there the same lag is a jump (two:
// into it and out of it); and a step back by 20 s, more than any buffer holds, is one whatever
// the buffer.
TEST(LidarStage, ALagTheReceiveBufferCanHoldIsNotAClockJump) {
  const auto starved = [](int k) { return 200'000 + (k >= 3000 && k < 4875 ? 400'000'000 : 0); };
  const auto stepped = [](int k) { return 200'000 + (k >= 3000 ? int64_t{20'000'000'000} : 0); };
  drivers::LidarConfig config;
  EXPECT_EQ(ClockJumpsOver10s(config, starved), 0u);
  EXPECT_EQ(ClockJumpsOver10s(config, stepped), 1u);
  config.rcvbuf_bytes = 256 * 1024;
  EXPECT_EQ(ClockJumpsOver10s(config, starved), 2u);  // into the lag, and out of it
}

TEST(LidarStage, RejectsAnUnknownModel) {
  drivers::LidarConfig config;
  config.model = "hdl64";
  EXPECT_THROW(LidarStage stage(config), std::invalid_argument);
}

}  // namespace
}  // namespace swlio::daemon

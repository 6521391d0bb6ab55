// Laps of a closed route (sim_laps.h): the lap period's arithmetic, which routes may be
// repeated, the trajectory's continuity across laps, and the replayed LiDAR packets.

#include "scenarios/sim_laps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sensors/lidar_sim.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/drivers/rs16_protocol.h"

namespace swlio::sim {
namespace {

namespace rs16 = drivers::rs16;

TEST(SimLaps, LapPeriodIsAWholeNumberOfPacketsAndRotations) {
  auto setup = MakeSimSetup("loop943", 1);
  ASSERT_TRUE(setup);
  const double route_s = SimDuration(*setup);
  const double period_s = LapPeriodS(*setup);
  EXPECT_GE(period_s, route_s);
  EXPECT_LT(period_s, route_s + 33.3 + 1e-6);
  // 1.332 ms packets and 100 ms rotations (600 rpm) meet every 33.3 s.
  const double steps = period_s / 33.3;
  EXPECT_NEAR(steps, std::round(steps), 1e-9);
}

TEST(SimLaps, OnlyARouteThatEndsWhereItStartsIsRepeated) {
  auto loop = MakeSimSetup("loop943", 1);
  ASSERT_TRUE(loop);
  EXPECT_TRUE(loop->trajectory->EndsWhereItStarts());
  std::string error;
  EXPECT_TRUE(RepeatRoute(&*loop, 3, &error)) << error;
  EXPECT_NEAR(SimDuration(*loop), 3.0 * LapPeriodS(*loop), 1e-9);
  EXPECT_FALSE(RepeatRoute(&*loop, 2, &error)) << "twice";

  auto open = MakeSimSetup("short", 1);
  ASSERT_TRUE(open);
  EXPECT_FALSE(open->trajectory->EndsWhereItStarts());
  EXPECT_FALSE(RepeatRoute(&*open, 2, &error));
  EXPECT_NE(error.find("does not end where"), std::string::npos) << error;
  EXPECT_FALSE(RepeatRoute(&*open, 0, &error));
  EXPECT_TRUE(RepeatRoute(&*open, 1, &error)) << "one lap is the route itself";
}

TEST(SimLaps, LapsJoinUpAndRepeatTheRoute) {
  auto setup = MakeSimSetup("loop943", 2);
  ASSERT_TRUE(setup);
  std::string error;
  ASSERT_TRUE(RepeatRoute(&*setup, 3, &error)) << error;
  const Trajectory& traj = *setup->trajectory;
  const double period_s = traj.lap_period_s();
  for (const double t : {0.0, 100.0, 512.3, period_s - 0.01}) {
    const Kinematics a = traj.At(t);
    const Kinematics b = traj.At(t + 2.0 * period_s);
    EXPECT_LT((a.p_world - b.p_world).norm(), 1e-9) << t;
    EXPECT_LT((a.v_world - b.v_world).norm(), 1e-9) << t;
  }
  // Across a lap boundary: standing still at the same pose on both sides.
  const Kinematics before = traj.At(period_s - 1e-3);
  const Kinematics after = traj.At(period_s + 1e-3);
  EXPECT_LT((before.p_world - after.p_world).norm(), 0.05);
  EXPECT_LT(lie::Log(before.R_world_body.transpose() * after.R_world_body).norm(), 0.01);
  EXPECT_LT(after.v_world.norm(), 1e-6);
}

// A short cut of a drive stands in for a closed route (LidarLaps does not check closure); the
// rpm makes one rotation exactly 75 packets (99.9 ms), so a lap can be as short as 3 s.
TEST(SimLaps, LaterLapsReplayTheFirstWithLaterTimes) {
  auto setup = MakeSimSetup("short", 3, 3.0);
  ASSERT_TRUE(setup);
  setup->lidar.rpm = 60e9 / 99'900'000.0;
  setup->lidar.clock.drift_ppm = 40.0;
  const double period_s = LapPeriodS(*setup);
  ASSERT_NEAR(period_s, std::ceil(3.0 / 0.0999) * 0.0999, 1e-9);
  setup->trajectory->Repeat(3, period_s);

  LidarLaps laps(*setup);
  std::vector<SimPacket> all;
  for (SimPacket p; laps.Next(&p);) all.push_back(p);
  const size_t per_lap = laps.packets_per_lap();
  ASSERT_GT(per_lap, 2000u);
  ASSERT_EQ(all.size(), 3 * per_lap);
  EXPECT_EQ(laps.msop_packets() + laps.difop_packets(), all.size());
  EXPECT_TRUE(
      std::is_sorted(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(per_lap),
                     [](const SimPacket& a, const SimPacket& b) { return a.t_rx_ns < b.t_rx_ns; }));
  for (size_t i = 0; i < per_lap; i += 97) {
    const SimPacket& a = all[i];
    const SimPacket& b = all[i + 2 * per_lap];
    const bool difop = a.dst_port != setup->lidar.msop_port;
    const size_t time_at = difop ? rs16::kDifopTime : rs16::kTimeOffset;
    EXPECT_EQ(b.t_rx_ns - a.t_rx_ns, SecToNs(2.0 * period_s)) << i;
    int64_t ta = 0, tb = 0;
    ASSERT_TRUE(rs16::ParseTime(a.bytes.data() + time_at, rs16::TimeFormat::kYmd, &ta));
    ASSERT_TRUE(rs16::ParseTime(b.bytes.data() + time_at, rs16::TimeFormat::kYmd, &tb));
    // Two laps later on the sensor's clock (drifting 40 ppm), to the µs of the format.
    EXPECT_NEAR(static_cast<double>(tb - ta), 2.0 * period_s * (1.0 + 40e-6) * 1e9, 1000.0) << i;
    // Everything else (azimuths, ranges, intensities, calibration) is the first lap's.
    for (size_t k = 0; k < a.bytes.size(); ++k) {
      if (k >= time_at && k < time_at + 10) continue;
      ASSERT_EQ(a.bytes[k], b.bytes[k]) << "packet " << i << " byte " << k;
    }
  }
  // The replayed azimuths are those a fresh cast two laps later has: the lap is a whole number
  // of rotations.
  LidarSimulator fresh(setup->world.get(), setup->trajectory.get(), setup->lidar, setup->seed);
  fresh.SkipTo(2.0 * period_s + 0.5);
  SimPacket f;
  do {
    ASSERT_TRUE(fresh.Next(&f));
  } while (f.dst_port != setup->lidar.msop_port);
  const auto time_of = [](const SimPacket& p) {
    return std::vector<uint8_t>(p.bytes.begin() + rs16::kTimeOffset,
                                p.bytes.begin() + rs16::kTimeOffset + 10);
  };
  const auto same = std::find_if(
      all.begin() + static_cast<std::ptrdiff_t>(2 * per_lap), all.end(),
      [&](const SimPacket& p) { return p.dst_port == f.dst_port && time_of(p) == time_of(f); });
  ASSERT_NE(same, all.end()) << "no replayed packet with the fresh one's time";
  for (size_t b = 0; b < static_cast<size_t>(rs16::kBlocks); ++b) {
    const size_t at = rs16::kFirstBlockOffset + b * rs16::kBlockBytes + 2;  // after the flag
    EXPECT_EQ(same->bytes[at], f.bytes[at]) << "block " << b;
    EXPECT_EQ(same->bytes[at + 1], f.bytes[at + 1]) << "block " << b;
  }
}

}  // namespace
}  // namespace swlio::sim

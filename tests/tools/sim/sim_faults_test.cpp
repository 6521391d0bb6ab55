// The live sender's fault injector: the loss channel's statistics, the byte-level damage it
// does, and which samples it withholds.

#include "live/sim_faults.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/lidar_sim.h"
#include "swlio/drivers/lidar_config.h"
#include "swlio/drivers/rs16_decoder.h"

namespace swlio::sim {
namespace {

TEST(FaultInjector, BurstyLossHasTheAskedRateAndBurstLength) {
  LiveFaults f;
  f.udp_loss_fraction = 0.05;
  f.udp_loss_burst_packets = 5.0;
  FaultInjector injector(f);
  std::vector<uint8_t> bytes(16);
  int lost = 0, bursts = 0;
  bool previous_lost = false;
  constexpr int kDatagrams = 200'000;
  for (int i = 0; i < kDatagrams; ++i) {
    const bool is_lost = !injector.PassDatagram(1.0, false, bytes);
    lost += is_lost ? 1 : 0;
    bursts += is_lost && !previous_lost ? 1 : 0;
    previous_lost = is_lost;
  }
  EXPECT_NEAR(static_cast<double>(lost) / kDatagrams, 0.05, 0.005);
  EXPECT_NEAR(static_cast<double>(lost) / bursts, 5.0, 0.5);
  EXPECT_EQ(injector.counts().msop_lost, static_cast<uint64_t>(lost));
}

TEST(FaultInjector, WindowsWithholdAndSilenceStops) {
  LiveFaults f;
  f.lidar_outages = {{2.0, 1.0}};
  f.imu_gaps = {{5.0, 0.2}};
  FaultInjector injector(f);
  std::vector<uint8_t> bytes(16);
  SimImuSample s;
  EXPECT_TRUE(injector.PassDatagram(1.99, false, bytes));
  EXPECT_FALSE(injector.PassDatagram(2.0, false, bytes));
  EXPECT_FALSE(injector.PassDatagram(2.99, true, bytes));
  EXPECT_TRUE(injector.PassDatagram(3.0, false, bytes));
  EXPECT_TRUE(injector.PassImu(4.99, &s));
  EXPECT_FALSE(injector.PassImu(5.1, &s));
  EXPECT_TRUE(injector.PassImu(5.2, &s));
  EXPECT_EQ(injector.counts().msop_withheld, 1u);
  EXPECT_EQ(injector.counts().difop_dropped, 1u);
  EXPECT_EQ(injector.counts().imu_withheld, 1u);
}

TEST(FaultInjector, OneRangeRewritesEveryReturnAndKeepsTheRest) {
  auto setup = MakeSimSetup("short", 1, 2.0);
  ASSERT_TRUE(setup.has_value());
  LidarSimulator lidar(setup->world.get(), setup->trajectory.get(), setup->lidar, 1);
  SimPacket packet;
  do {
    ASSERT_TRUE(lidar.Next(&packet));
  } while (packet.dst_port != setup->lidar.msop_port);
  LiveFaults f;
  f.lidar_one_range = {{0.0, 10.0}};
  f.one_range_m = 0.6;
  FaultInjector injector(f);
  ASSERT_TRUE(injector.PassDatagram(0.5, false, packet.bytes));
  drivers::LidarConfig config;
  drivers::Rs16Decoder decoder(config);
  drivers::LidarPacketDecoder::ReturnBuffer out{};
  drivers::LidarPacketSummary summary;
  ASSERT_EQ(decoder.DecodeData(packet.bytes, out, &summary), drivers::DecodeStatus::kOk);
  ASSERT_GT(summary.returns, 100u);
  for (size_t i = 0; i < summary.returns; ++i) EXPECT_NEAR(out[i].range_m, 0.6, 1e-6);
  EXPECT_EQ(injector.counts().msop_one_range, 1u);
}

TEST(FaultInjector, NonFiniteValuesAndGarbageAtTheirRates) {
  LiveFaults f;
  f.imu_nonfinite_fraction = 0.01;
  f.serial_garbage_bytes_per_s = 2000.0;
  FaultInjector injector(f);
  int bad = 0;
  std::vector<uint8_t> garbage;
  for (int i = 0; i < 40'000; ++i) {  // 100 s at 400 Hz
    const double t_s = i / 400.0;
    SimImuSample s;
    s.acc_mps2 = {0.0, 0.0, 9.8};
    ASSERT_TRUE(injector.PassImu(t_s, &s));
    bad += s.acc_mps2.allFinite() ? 0 : 1;
    injector.AppendGarbage(t_s, &garbage);
  }
  EXPECT_NEAR(bad, 400, 80);
  EXPECT_EQ(injector.counts().imu_nonfinite, static_cast<uint64_t>(bad));
  EXPECT_NEAR(static_cast<double>(garbage.size()), 2000.0 * 99.9975, 2.0);
}

}  // namespace
}  // namespace swlio::sim

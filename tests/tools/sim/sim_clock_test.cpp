// The clock model on the simulator's sensor clocks: Xsens SampleTimeFine (offset, ±50 ppm drift,
// USB-like bursts and stalls) and the RS16 header clock (UTC-like, ±20 ppm), mapped to host
// time within 0.5 ms of the truth.

#include <gtest/gtest.h>

#include <cmath>

#include "scenarios/sim_setup.h"
#include "swlio/core/time.h"
#include "swlio/drivers/clock_model.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/xsens/mtdata2.h"

namespace swlio::sim {
namespace {

TEST(SimClock, ImuSampleTimeFineMapsToHostWithinHalfAMillisecond) {
  for (const uint64_t seed : {1u, 2u, 3u}) {
    auto setup = MakeSimSetup("short", seed, 40.0);
    ASSERT_TRUE(setup);
    setup->imu.clock.drift_ppm = seed == 1 ? 100.0 : setup->imu.clock.drift_ppm;
    const auto imu = SimulateImu(*setup->trajectory, setup->imu, seed);
    drivers::ClockModelConfig config;
    config.wrap_period_ns = drivers::xsens::SampleTimeFineToNs(0xFFFFFFFFu) + 100'000;
    config.fixed_latency_ns = SecToNs(setup->imu.frame_bytes * 10.0 / setup->imu.baud);
    drivers::ClockModel model(config);
    double worst_ms = 0.0;
    for (const SimImuSample& s : imu) {
      const int64_t stf_ns = drivers::xsens::SampleTimeFineToNs(s.sample_time_fine);
      model.Observe(stf_ns, s.t_rx_ns);
      if (s.t_true_ns > 5 * kNsPerSec) {
        worst_ms = std::max(worst_ms, std::abs(NsToSec(model.ToHost(stf_ns) - s.t_true_ns)) * 1e3);
      }
    }
    EXPECT_LT(worst_ms, 0.5) << "seed " << seed << ", drift " << setup->imu.clock.drift_ppm;
    EXPECT_NEAR(model.stats().drift_ppm, -setup->imu.clock.drift_ppm, 3.0);
  }
}

TEST(SimClock, SetImuWrapAtMakesSampleTimeFineWrapThere) {
  auto setup = MakeSimSetup("short", 1, 8.0);
  ASSERT_TRUE(setup);
  setup->imu.clock.drift_ppm = 80.0;
  SetImuWrapAt(&*setup, 5.0);
  const auto imu = SimulateImu(*setup->trajectory, setup->imu, 1);
  size_t wraps = 0;
  double wrap_t_s = -1.0;
  for (size_t i = 1; i < imu.size(); ++i) {
    if (imu[i].sample_time_fine < imu[i - 1].sample_time_fine) {
      ++wraps;
      wrap_t_s = NsToSec(imu[i].t_true_ns);
    }
  }
  EXPECT_EQ(wraps, 1u);
  EXPECT_NEAR(wrap_t_s, 5.0, 0.003);  // the first sample after it (400 Hz)
}

TEST(SimClock, LidarHeaderTimeMapsToHostWithinHalfAMillisecond) {
  auto setup = MakeSimSetup("short", 4, 9.0);
  ASSERT_TRUE(setup);
  LidarSimulator lidar(setup->world.get(), setup->trajectory.get(), setup->lidar, 4);
  drivers::Rs16Decoder decoder{drivers::LidarConfig{}};
  drivers::LidarPacketDecoder::ReturnBuffer buffer;
  drivers::ClockModelConfig config;  // a packet arrives after its 24 firings + network latency
  config.fixed_latency_ns = 23 * 55'500 + 15 * 2'800 + SecToNs(setup->lidar.latency_s);
  drivers::ClockModel model(config);
  SimPacket packet;
  std::vector<SimReturn> truth;
  double worst_ms = 0.0;
  while (lidar.Next(&packet, &truth)) {
    if (decoder.Classify(packet.bytes) != drivers::LidarPacketKind::kData) continue;
    drivers::LidarPacketSummary summary;
    ASSERT_EQ(decoder.DecodeData(packet.bytes, buffer, &summary), drivers::DecodeStatus::kOk);
    model.Observe(summary.t_sensor_ns, packet.t_rx_ns);
    if (truth[0].t_true_ns > 6 * kNsPerSec) {
      worst_ms =
          std::max(worst_ms,
                   std::abs(NsToSec(model.ToHost(summary.t_sensor_ns) - truth[0].t_true_ns)) * 1e3);
    }
  }
  EXPECT_LT(worst_ms, 0.5);
  EXPECT_NEAR(model.stats().drift_ppm, -setup->lidar.clock.drift_ppm, 3.0);
}

}  // namespace
}  // namespace swlio::sim

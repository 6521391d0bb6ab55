// The sensor clocks of a simulated drive, 100 ppm off the host and offset by the simulator's
// amounts, mapped to host time the way the daemon and the replay do (ImuStage via the
// recording reader, LidarStage): within 0.5 ms of the truth once the models have a few
// seconds of data, through USB-serial bursts and stalls.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "sensors/imu_sim.h"
#include "swlio/daemon/recording/recording_reader.h"
#include "swlio/daemon/sensors/lidar_stage.h"
#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/rs16_decoder.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kSettleNs = 5'000'000'000;  // the models' first windows

TEST(ClockMapping, SimulatedClocksAt100PpmMapWithinHalfAMillisecond) {
  auto setup = sim::MakeSimSetup("short", 3, 20.0);
  ASSERT_TRUE(setup.has_value());
  setup->imu.clock.drift_ppm = 100.0;
  setup->lidar.clock.drift_ppm = -100.0;
  const auto dir = test::MakeTempDir("clock_mapping");
  sim::RecordingStats stats;
  std::string error;
  ASSERT_TRUE(sim::WriteRecording(*setup, dir, &stats, &error)) << error;

  // IMU: every mapped sample against the time it was taken.
  drivers::LidarConfig lidar;
  auto reader = RecordingReader::Open(dir, lidar, {}, &error);
  ASSERT_NE(reader, nullptr) << error;
  const std::vector<sim::SimImuSample> truth =
      sim::SimulateImu(*setup->trajectory, setup->imu, setup->seed);
  size_t k = 0;
  double worst_imu_ms = 0.0;
  RecordingEvent e;
  while (reader->Next(&e)) {
    if (e.kind != RecordingEvent::Kind::kImu) continue;
    ASSERT_LT(k, truth.size());
    const int64_t t_true = sim::kFileHostStartNs + truth[k++].t_true_ns;
    if (t_true - sim::kFileHostStartNs < kSettleNs) continue;
    worst_imu_ms = std::max(worst_imu_ms, std::abs(double(e.imu.t_ns - t_true)) * 1e-6);
  }
  EXPECT_EQ(k, truth.size()) << "no sample lost";
  EXPECT_LT(worst_imu_ms, 0.5);
  EXPECT_NEAR(reader->stats().imu_clock.drift_ppm, -100.0, 2.0);

  // LiDAR: every packet's header time mapped, against the simulator's clock inverted.
  LidarStage stage(lidar);
  drivers::Rs16Decoder decoder(lidar);
  drivers::LidarPacketDecoder::ReturnBuffer buffer{};
  auto pcap = drivers::PcapReader::Open((dir / "lidar.pcap").string(), {}, &error);
  ASSERT_NE(pcap, nullptr) << error;
  drivers::UdpDatagram d;
  double worst_lidar_ms = 0.0;
  size_t packets = 0;
  HostSweep sweep;
  while (pcap->Next(&d)) {
    stage.Add(d.payload, d.t_ns);
    while (stage.Pop(&sweep)) {
    }
    drivers::LidarPacketSummary summary;
    if (decoder.Classify(d.payload) != drivers::LidarPacketKind::kData ||
        decoder.DecodeData(d.payload, buffer, &summary) != drivers::DecodeStatus::kOk) {
      continue;
    }
    const double sensor_s = static_cast<double>(summary.t_sensor_ns) * 1e-9;
    const auto t_true =
        static_cast<int64_t>(std::llround(setup->lidar.clock.ToHost(sensor_s) * 1e9)) +
        sim::kFileHostStartNs;
    ++packets;
    if (t_true - sim::kFileHostStartNs < kSettleNs) continue;
    const int64_t mapped = stage.ToHost(summary.t_sensor_ns);
    worst_lidar_ms = std::max(worst_lidar_ms, std::abs(double(mapped - t_true)) * 1e-6);
  }
  EXPECT_GT(packets, 10'000u);
  EXPECT_LT(worst_lidar_ms, 0.5);
  EXPECT_NEAR(stage.clock().drift_ppm, 100.0, 2.0);
  std::cout << "[ clock ] worst after 5 s: IMU " << worst_imu_ms << " ms, LiDAR " << worst_lidar_ms
            << " ms\n";
}

}  // namespace
}  // namespace swlio::daemon

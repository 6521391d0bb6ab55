// RecordingReader on a simulated recording: the decoders, assembler and clock models give IMU
// samples and scans on the host clock, in processing order, close to the simulator's truth.

#include "swlio/daemon/recording/recording_reader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/time.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

TEST(RecordingReader, SimulatedRecordingOnTheHostClock) {
  constexpr double kSeconds = 5.0;
  const auto dir = test::MakeTempDir("recreader");
  auto setup = sim::MakeSimSetup("short", 21, kSeconds);
  ASSERT_TRUE(setup);
  sim::RecordingStats written;
  std::string error;
  ASSERT_TRUE(sim::WriteRecording(*setup, dir, &written, &error)) << error;

  auto reader = RecordingReader::Open(dir, drivers::LidarConfig{}, drivers::ImuConfig{}, &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto truth = sim::SimulateImu(*setup->trajectory, setup->imu, 21);
  RecordingEvent e;
  size_t imu = 0, scans = 0, points = 0;
  int64_t last_imu_ns = 0, last_scan_end_ns = 0;
  double worst_imu_ms = 0.0;
  while (reader->Next(&e)) {
    if (e.kind == RecordingEvent::Kind::kImu) {
      ASSERT_LT(imu, truth.size());
      const int64_t true_host = truth[imu].t_true_ns + sim::kFileHostStartNs;
      if (truth[imu].t_true_ns > 2 * kNsPerSec) {
        worst_imu_ms = std::max(worst_imu_ms, std::abs(NsToSec(e.imu.t_ns - true_host)) * 1e3);
      }
      EXPECT_GE(e.imu.t_ns, last_imu_ns);
      last_imu_ns = e.imu.t_ns;
      ++imu;
    } else {
      EXPECT_GE(last_imu_ns, e.scan.t_end_ns - 5 * kNsPerMs) << "IMU covers the scan";
      EXPECT_GT(e.scan.t_end_ns, last_scan_end_ns);
      if (!e.scan.partial) {
        EXPECT_NEAR(NsToSec(e.scan.t_end_ns - e.scan.t_start_ns), 0.1, 0.01);
      }
      last_scan_end_ns = e.scan.t_end_ns;
      points += e.scan.points.size();
      ++scans;
    }
  }
  EXPECT_EQ(imu, written.imu_frames);
  EXPECT_NEAR(static_cast<double>(scans), kSeconds * 10.0, 2.0);
  EXPECT_EQ(points, written.valid_returns);
  EXPECT_LT(worst_imu_ms, 0.5);
  EXPECT_EQ(reader->stats().missing_packets, 0u);
  EXPECT_EQ(reader->stats().imu_checksum_errors, 0u);
}

}  // namespace
}  // namespace swlio::daemon

// RecordingReader's optional streams on a simulated recording: GNSS fixes from the GnssPvtData
// items of imu.xbus and wheel odometry from can.log, merged by time with the IMU samples, only
// when asked for; unusable fixes and unreadable CAN lines are counted, never fatal; the
// manifest's rig blocks read back.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "sensors/gnss_sim.h"
#include "sensors/wheel_sim.h"
#include "swlio/core/time.h"
#include "swlio/daemon/recording/recording_reader.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr uint64_t kSeed = 31;
constexpr double kSeconds = 4.0;

/// A 4 s recording with a GNSS outage (fixType 0 items) from 2.0 to 2.6 s.
struct Recording {
  std::filesystem::path dir;
  sim::SimSetup setup;
  sim::RecordingStats written;
};

Recording Write(const std::string& tag) {
  Recording r{test::MakeTempDir(tag), std::move(*sim::MakeSimSetup("short", kSeed, kSeconds)), {}};
  r.setup.gnss.outages = {{2.0, 0.6}};
  std::string error;
  EXPECT_TRUE(sim::WriteRecording(r.setup, r.dir, &r.written, &error)) << error;
  return r;
}

struct Events {
  std::vector<RecordingEvent> all;
  size_t imu = 0, scans = 0, gnss = 0, wheel = 0;
};

Events ReadAll(RecordingReader* reader) {
  Events out;
  RecordingEvent e;
  while (reader->Next(&e)) {
    out.imu += e.kind == RecordingEvent::Kind::kImu;
    out.scans += e.kind == RecordingEvent::Kind::kScan;
    out.gnss += e.kind == RecordingEvent::Kind::kGnss;
    out.wheel += e.kind == RecordingEvent::Kind::kWheel;
    e.scan.points.clear();  // keep the copies small
    out.all.push_back(e);
  }
  return out;
}

int64_t TimeOf(const RecordingEvent& e) {
  switch (e.kind) {
    case RecordingEvent::Kind::kImu:
      return e.imu.t_ns;
    case RecordingEvent::Kind::kScan:
      return e.scan.t_end_ns;
    case RecordingEvent::Kind::kGnss:
      return e.gnss.t_ns;
    case RecordingEvent::Kind::kWheel:
      return e.wheel.t_ns;
  }
  return 0;
}

RecordingReadOptions AllStreams(const std::filesystem::path& dir) {
  RecordingReadOptions options;
  options.gnss = true;
  options.wheel = ManifestWheelCan(dir);
  EXPECT_TRUE(options.wheel.has_value()) << "the manifest states the CAN layout";
  return options;
}

TEST(RecordingReaderStreams, GnssAndWheelEventsInTimeOrderWhenAsked) {
  const Recording rec = Write("rr_streams");
  std::string error;
  auto reader = RecordingReader::Open(rec.dir, {}, {}, AllStreams(rec.dir), &error);
  ASSERT_NE(reader, nullptr) << error;
  const Events ev = ReadAll(reader.get());
  const RecordingStats& stats = reader->stats();
  EXPECT_EQ(ev.imu, rec.written.imu_frames);
  EXPECT_GT(ev.scans, 30u);
  EXPECT_GT(ev.gnss, 8u);     // 4 Hz from 1 s on, less the outage
  EXPECT_GT(ev.wheel, 190u);  // 50 Hz
  EXPECT_EQ(ev.gnss + stats.gnss_rejected, rec.written.gnss_items);
  EXPECT_EQ(stats.gnss_rejected, rec.written.gnss_no_fix) << "the outage's fixType 0 items";
  EXPECT_GT(rec.written.gnss_no_fix, 1u);
  EXPECT_EQ(ev.gnss, stats.gnss_fixes);
  EXPECT_EQ(ev.wheel, rec.written.wheel_frames);
  EXPECT_EQ(ev.wheel, stats.wheel_samples);
  EXPECT_EQ(stats.wheel_frames_dropped, 0u);
  EXPECT_EQ(stats.wheel_log_missing, 0u);
  // Non-scan events in nondecreasing time; none at or before a scan's end comes after it.
  int64_t last_ns = 0, last_scan_end_ns = 0;
  for (const RecordingEvent& e : ev.all) {
    const int64_t t = TimeOf(e);
    if (e.kind == RecordingEvent::Kind::kScan) {
      last_scan_end_ns = t;
      continue;
    }
    EXPECT_GE(t, last_ns);
    EXPECT_GT(t, last_scan_end_ns);
    last_ns = t;
  }
}

TEST(RecordingReaderStreams, FixesAndWheelSamplesMatchTheSimulation) {
  const Recording rec = Write("rr_truth");
  std::string error;
  auto reader = RecordingReader::Open(rec.dir, {}, {}, AllStreams(rec.dir), &error);
  ASSERT_NE(reader, nullptr) << error;
  const Events ev = ReadAll(reader.get());
  const auto imu = sim::SimulateImu(*rec.setup.trajectory, rec.setup.imu, kSeed);
  std::vector<sim::SimGnssFix> fixes =
      sim::SimulateGnss(*rec.setup.trajectory, rec.setup.gnss, imu, kSeed);
  std::erase_if(fixes, [](const sim::SimGnssFix& f) { return !f.has_fix; });
  const auto wheels = sim::SimulateWheels(*rec.setup.trajectory, rec.setup.wheel, kSeed);
  const std::optional<ManifestGnss> gnss = ManifestGnssSetup(rec.dir);
  ASSERT_TRUE(gnss.has_value());
  const LocalEnu enu(gnss->origin);
  size_t g = 0, w = 0;
  for (const RecordingEvent& e : ev.all) {
    if (e.kind == RecordingEvent::Kind::kGnss) {
      ASSERT_LT(g, fixes.size());
      const sim::SimGnssFix& f = fixes[g++];
      const Eigen::Vector3d p = enu.ToEnu({e.gnss.lat_deg, e.gnss.lon_deg, e.gnss.height_m});
      EXPECT_LT((p - (f.p_enu_true_m + f.error_enu_m)).norm(), 0.01);
      EXPECT_LT(std::abs(e.gnss.t_ns - (sim::kFileHostStartNs + f.t_true_ns)), kNsPerMs)
          << "the IMU sample's host time";
      EXPECT_NEAR(e.gnss.h_acc_m, f.pvt.h_acc_mm * 1e-3, 1e-9);
      EXPECT_EQ(e.gnss.fix_type, 3);
    } else if (e.kind == RecordingEvent::Kind::kWheel) {
      ASSERT_LT(w, wheels.size());
      const sim::SimWheelSample& s = wheels[w++];
      EXPECT_EQ(e.wheel.t_ns, (sim::kFileHostStartNs + s.t_rx_ns) / 1000 * 1000);
      EXPECT_NEAR(e.wheel.linear_velocity_mps, 0.5 * (s.left_mps + s.right_mps), 1e-9);
    }
  }
  EXPECT_EQ(g, fixes.size());
  EXPECT_EQ(w, wheels.size());
}

TEST(RecordingReaderStreams, NoneUnlessAsked) {
  const Recording rec = Write("rr_default");
  std::string error;
  auto reader = RecordingReader::Open(rec.dir, {}, {}, &error);
  ASSERT_NE(reader, nullptr) << error;
  const Events ev = ReadAll(reader.get());
  EXPECT_EQ(ev.gnss, 0u);
  EXPECT_EQ(ev.wheel, 0u);
  EXPECT_EQ(ev.imu, rec.written.imu_frames);
  EXPECT_EQ(reader->stats().gnss_fixes + reader->stats().gnss_rejected, 0u);
}

TEST(RecordingReaderStreams, BadLinesAndMissingLogsAreCountedNotFatal) {
  const Recording rec = Write("rr_bad");
  {
    std::ofstream log(rec.dir / "can.log", std::ios::app);
    log << "(100.5) can0 201#ZZ\nnot a candump line\n";
  }
  std::string error;
  auto reader = RecordingReader::Open(rec.dir, {}, {}, AllStreams(rec.dir), &error);
  ASSERT_NE(reader, nullptr) << error;
  const Events ev = ReadAll(reader.get());
  EXPECT_EQ(reader->stats().wheel_frames_dropped, 2u);
  EXPECT_EQ(ev.wheel, rec.written.wheel_frames);
  EXPECT_EQ(reader->stats().gnss_rejected, rec.written.gnss_no_fix);

  std::filesystem::remove(rec.dir / "can.log");
  reader = RecordingReader::Open(rec.dir, {}, {}, AllStreams(rec.dir), &error);
  ASSERT_NE(reader, nullptr) << error;
  EXPECT_EQ(ReadAll(reader.get()).wheel, 0u);
  EXPECT_EQ(reader->stats().wheel_log_missing, 1u);

  RecordingReadOptions bad;
  bad.wheel = drivers::CanConfig{};  // no signals: not a layout
  EXPECT_EQ(RecordingReader::Open(rec.dir, {}, {}, bad, &error), nullptr);
  EXPECT_NE(error.find("layout"), std::string::npos) << error;
}

TEST(RecordingReaderStreams, ManifestStatesTheRig) {
  const Recording rec = Write("rr_manifest");
  const std::optional<Eigen::Isometry3d> T_imu_base = ManifestWheelExtrinsic(rec.dir);
  ASSERT_TRUE(T_imu_base.has_value());
  EXPECT_TRUE(T_imu_base->isApprox(rec.setup.wheel.T_imu_base, 1e-9));
  const std::optional<ManifestGnss> gnss = ManifestGnssSetup(rec.dir);
  ASSERT_TRUE(gnss.has_value());
  EXPECT_DOUBLE_EQ(gnss->origin.lat_deg, rec.setup.gnss.origin.lat_deg);
  EXPECT_DOUBLE_EQ(gnss->origin.lon_deg, rec.setup.gnss.origin.lon_deg);
  EXPECT_DOUBLE_EQ(gnss->origin.height_m, rec.setup.gnss.origin.height_m);
  EXPECT_TRUE(gnss->antenna_imu_m.isApprox(rec.setup.gnss.p_imu_antenna_m, 1e-9));
  EXPECT_DOUBLE_EQ(gnss->rate_hz, 4.0);
  EXPECT_DOUBLE_EQ(gnss->sigma_h_m, rec.setup.gnss.noise.sigma_h_m);
  EXPECT_DOUBLE_EQ(gnss->sigma_v_m, rec.setup.gnss.noise.sigma_v_m);
  // The LiDAR extrinsic's lines are still the only ones its reader matches.
  const std::optional<Eigen::Isometry3d> T_imu_lidar = ManifestExtrinsic(rec.dir);
  ASSERT_TRUE(T_imu_lidar.has_value());
  EXPECT_TRUE(T_imu_lidar->isApprox(rec.setup.lidar.T_imu_lidar, 1e-6));
  // --no-gnss / --no-wheel: no blocks, no can.log.
  sim::SimSetup quiet = std::move(*sim::MakeSimSetup("short", kSeed, 1.5));
  quiet.imu.gnss_pvt_period_s = 0.0;
  quiet.wheel.enabled = false;
  const auto dir = test::MakeTempDir("rr_quiet");
  sim::RecordingStats stats;
  std::string error;
  ASSERT_TRUE(sim::WriteRecording(quiet, dir, &stats, &error)) << error;
  EXPECT_FALSE(std::filesystem::exists(dir / "can.log"));
  EXPECT_EQ(stats.gnss_items, 0u);
  EXPECT_FALSE(ManifestGnssSetup(dir).has_value());
  EXPECT_FALSE(ManifestWheelExtrinsic(dir).has_value());
  EXPECT_FALSE(ManifestWheelCan(dir).has_value());
}

}  // namespace
}  // namespace swlio::daemon

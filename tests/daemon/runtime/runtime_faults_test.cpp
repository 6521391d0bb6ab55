// Fault injection end to end (issue 9): the simulator streams a drive live into a Runtime and
// injects one fault (sim_faults.h); each test states what the daemon must do, checks it, and
// prints the health it published over DDS while it happened. The `short` drive stands still
// for its first seconds (the static initialization, tracking from about 1.5 s); faults of the
// sensor streams start at 5 s, those that test carrying the pose on at 6 s, while driving.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "live_drive.h"

namespace swlio::daemon {
namespace {

using test::LiveDrive;
using test::LiveDriveResult;
using test::RunLiveDrive;

constexpr const char* kEstimator = "swlio: estimator";
constexpr const char* kLidar = "swlio: lidar";
constexpr const char* kImu = "swlio: imu";

LiveDrive Drive(double duration_s, uint32_t domain) {
  LiveDrive d;
  d.duration_s = duration_s;
  // 1×: at 2× a simulator that shares the 2 cores with another test fell behind by more than
  // the clock models take for a backlog (a CI run read that as an IMU clock jump).
  d.speed = 1.0;
  d.dds_domain = domain;  // one per test: 141..153 (live_drive.h)
  return d;
}

bool Carried(TrackingState t) {
  return t == TrackingState::kTracking || t == TrackingState::kDegraded;
}

/// Whether every published pose is finite; names the first one that is not.
testing::AssertionResult AllPosesFinite(const LiveDriveResult& r) {
  for (size_t i = 0; i < r.poses.size(); ++i) {
    const auto& m = r.poses[i].msg;
    bool finite = true;
    for (double v : m.pose.position_m) finite = finite && std::isfinite(v);
    for (double v : m.pose.orientation_xyzw) finite = finite && std::isfinite(v);
    if (!finite) {
      return testing::AssertionFailure()
             << "pose " << i << " of " << r.poses.size() << " at " << r.SimTime(m.t_ns) << " s: p "
             << m.pose.position_m[0] << " " << m.pose.position_m[1] << " " << m.pose.position_m[2]
             << ", q " << m.pose.orientation_xyzw[3];
    }
  }
  if (r.final.publisher.non_finite > 0) {  // kept from DDS by the publisher (see its test)
    std::cout << "[ note ] the publisher held back " << r.final.publisher.non_finite
              << " non-finite poses\n";
  }
  return testing::AssertionSuccess();
}

/// Position variance (x) of the last pose stamped before simulation time t_s.
double PositionVarianceBefore(const LiveDriveResult& r, double t_s) {
  double v = -1.0;
  for (const auto& p : r.poses) {
    if (r.SimTime(p.msg.t_ns) < t_s) v = p.msg.covariance[0];
  }
  return v;
}

// 5 % of the MSOP datagrams lost in bursts of 5 on average: every loss is counted as missing,
// the sweeps are used with their holes, the estimate keeps tracking.
TEST(RuntimeFaults, BurstyUdpLossIsCountedAndTrackingGoesOn) {
  LiveDrive drive = Drive(12.0, 141);
  drive.faults.udp_loss_fraction = 0.05;
  drive.faults.udp_loss_burst_packets = 5.0;
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kLidar);
  const uint64_t lost = r.stats.faults.msop_lost;
  const uint64_t sent = r.stats.udp_sent;
  EXPECT_NEAR(static_cast<double>(lost) / static_cast<double>(lost + sent), 0.05, 0.02);
  // Losses at the very start (before the first packet) or after the last cannot be seen.
  EXPECT_NEAR(static_cast<double>(r.final.optimizer.lidar.missing_packets),
              static_cast<double>(lost), 0.05 * static_cast<double>(lost) + 10.0);
  if (r.stats.max_lateness_ms < 200.0) {  // a sender seconds behind looks like a clock step
    EXPECT_EQ(r.final.optimizer.lidar_clock.jumps, 0u) << "losses are not clock jumps";
  }
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
  EXPECT_GE(r.poses.size(), 1000u);
}

// The LiDAR is out for 2 s: the pose keeps coming from the IMU with a growing covariance, the
// health says degraded (IMU only), and LiDAR tracking resumes when the packets come back.
TEST(RuntimeFaults, TwoSecondLidarOutageIsBridgedAndReported) {
  LiveDrive drive = Drive(12.0, 142);
  drive.faults.lidar_outages = {{6.0, 2.0}};
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kEstimator);
  EXPECT_GE(r.PosesBetween(6.3, 8.0), 400u) << "IMU-rate poses through the outage";
  const double before = PositionVarianceBefore(r, 6.0);
  const double late = PositionVarianceBefore(r, 7.9);
  EXPECT_GT(before, 0.0);
  EXPECT_GT(late, 4.0 * before) << "the covariance grows while the IMU alone carries the pose";
  const HealthSnapshot& during = r.HealthAt(7.8);
  EXPECT_EQ(during.optimizer.tracking, TrackingState::kDegraded);
  EXPECT_GT(during.optimizer.imu_only_s * r.speed, 1.0);  // health counts host seconds
  EXPECT_TRUE(r.PublishedSaid(kEstimator, "IMU only"));
  EXPECT_EQ(r.HealthAt(11.5).optimizer.tracking, TrackingState::kTracking) << "resumed";
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
}

// 200 ms without IMU frames: counted as missing packets, ridden through without a restart.
TEST(RuntimeFaults, ImuGapIsCountedAndRiddenThrough) {
  LiveDrive drive = Drive(8.0, 143);
  drive.faults.imu_gaps = {{5.0, 0.2}};
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kImu);
  EXPECT_GE(r.stats.faults.imu_withheld, 70u);
  EXPECT_EQ(r.final.propagator.decode.missing_packets, r.stats.faults.imu_withheld);
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
}

// The IMU's bytes are held for 6 s (a kernel tty worker starved that long, measured here under
// load: docs/notes/2026-12-03-busy-machine.md) and then arrive at once, ~2,400 samples in a
// few reads (the pty paces them: each read takes at most 4 KiB). None is lost inside the daemon
// (no queue drops), the lateness is no clock jump, the stale samples give one pose per read,
// the sweeps that waited are thinned, and tracking goes on.
TEST(RuntimeFaults, ASerialStallOfSecondsLosesNoSampleAndIsNoClockJump) {
  LiveDrive drive = Drive(14.0, 156);
  drive.faults.serial_stalls = {{5.0, 6.0}};
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kImu);
  r.ShowPublished(kEstimator);
  EXPECT_EQ(r.stats.imu_bytes_dropped, 0u);
  EXPECT_GE(r.stats.imu_backlog_max_wait_ms, 5000.0) << "the bytes were held";
  for (const QueueCounters& q : r.final.queues) EXPECT_EQ(q.dropped, 0u) << q.name;
  EXPECT_EQ(r.final.propagator.decode.missing_packets, 0u);
  EXPECT_EQ(r.final.propagator.clock_jumps, 0u);
  // ~2,300 samples are read over 250 ms late; each read publishes only its newest. How many
  // reads the backlog takes depends on how the tty hands it over (a SCHED_FIFO reader takes
  // each chunk as it comes: 908 coalesced here, 2026-12-04); without coalescing it is 0.
  EXPECT_GE(r.final.propagator.poses_coalesced, 500u) << "not thousands of stale poses";
  EXPECT_GE(r.final.optimizer.dropped_waiting, 1u) << "60 sweeps waited, 20 are kept";
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
  // Timely again after the stall: 400 Hz, unless the simulator itself was starved (a loaded
  // CI machine sent up to 1.6 s late, which the daemon's poses then are too).
  const size_t after = r.PosesBetween(12.0, 14.0);
  EXPECT_GE(after, r.stats.max_lateness_ms < 200.0 ? 700u : 1u) << "poses after the stall";
}

// The serial adapter is unplugged for 1 s and comes back under the same name: the reader
// notices, re-opens it and streams again; the estimate carries on (re-initializing if the gap
// made that necessary) and poses resume.
TEST(RuntimeFaults, SerialUnplugAndReplugResumes) {
  LiveDrive drive = Drive(12.0, 144);
  drive.faults.serial_unplugs = {{6.0, 1.0}};
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kImu);
  r.ShowPublished(kEstimator);
  EXPECT_EQ(r.stats.faults.unplugs, 1u);
  EXPECT_GE(r.final.imu_rx.disconnects, 1u);
  EXPECT_GE(r.final.imu_rx.opens, 2u);
  EXPECT_TRUE(r.PublishedSaid(kImu, "no samples") || r.PublishedSaid(kImu, "not open"));
  EXPECT_GE(r.PosesBetween(9.0, 12.0), 400u) << "poses again after the replug";
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
}

// The LiDAR's clock is set an hour ahead mid-drive (GPS time arriving): the clock model
// reports the jump, re-locks, and tracking goes on without a restart.
TEST(RuntimeFaults, LidarClockJumpIsReportedAndTrackingGoesOn) {
  LiveDrive drive = Drive(12.0, 145);
  drive.adjust_setup = [](sim::SimSetup* s) {
    s->lidar.clock.step_at_s = 6.0;
    s->lidar.clock.step_s = 3600.0;
  };
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kLidar);
  EXPECT_GE(r.final.optimizer.lidar_clock.jumps, 1u);
  if (r.stats.max_lateness_ms < 200.0) {
    EXPECT_EQ(r.final.optimizer.lidar_clock.jumps, 1u);
  }
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
  const uint64_t at_jump = r.HealthAt(6.0).optimizer.processed;
  EXPECT_GE(r.final.optimizer.processed, at_jump + 45u) << "sweeps after the jump are used";
  bool warned = false;
  for (const auto& h : r.published_health) {
    for (const auto& st : h.msg.status) {
      warned = warned || (st.name == "swlio: lidar" && st.level == ipc::DiagnosticLevel::kWarn &&
                          st.message == "streaming; clock jumped");
    }
  }
  EXPECT_TRUE(warned) << "the published health says that the LiDAR clock jumped";
}

// The Xsens SampleTimeFine counter (100 µs ticks) wraps at 2³² mid-drive: it is unwrapped, not
// taken for a clock jump, and no sample is lost.
TEST(RuntimeFaults, ImuCounterWrapIsSeamless) {
  LiveDrive drive = Drive(8.0, 146);
  drive.adjust_setup = [](sim::SimSetup* s) { sim::SetImuWrapAt(s, 5.0); };
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kImu);
  EXPECT_EQ(r.final.propagator.decode.missing_packets, 0u);
  EXPECT_GE(r.PosesBetween(5.5, 8.0), 800u);
  if (r.stats.max_lateness_ms >= 200.0) {  // a sender that far behind mimics a clock step
    std::cout << "[ note ] the simulator fell " << r.stats.max_lateness_ms << " ms behind\n";
    return;
  }
  EXPECT_EQ(r.final.propagator.clock_jumps, 0u);
  // (A sample or two can be dropped as out of order while the clock model locks at start.)
  EXPECT_EQ(r.final.propagator.dropped, r.HealthAt(4.5).propagator.dropped) << "none at the wrap";
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
}

// Random bytes between the frames (electrical noise on the line): the framer skips and counts
// them and loses at most the frames the garbage happened to touch.
TEST(RuntimeFaults, SerialGarbageIsSkippedAndCounted) {
  LiveDrive drive = Drive(8.0, 147);
  drive.faults.serial_garbage_bytes_per_s = 2000.0;
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kImu);
  EXPECT_GE(r.stats.faults.garbage_bytes, 12000u);
  EXPECT_GE(ImuSkippedBytes(r.final), r.stats.faults.garbage_bytes / 2);
  const double frames = 400.0 * drive.duration_s;
  EXPECT_GE(static_cast<double>(r.final.propagator.decode.samples), 0.97 * frames);
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
}

// 1 % of the IMU frames carry NaN or ±Inf in the acceleration (checksums intact): each such
// sample is dropped and counted; no published pose is non-finite.
TEST(RuntimeFaults, NonFiniteImuValuesAreDropped) {
  LiveDrive drive = Drive(8.0, 148);
  drive.faults.imu_nonfinite_fraction = 0.01;
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kImu);
  EXPECT_GE(r.stats.faults.imu_nonfinite, 15u);
  // Every damaged frame that arrived is dropped and counted. On a loaded machine the pty can
  // lose bytes (the simulator falls behind; the reader then counts missing frames), and with
  // them damaged frames, which only lowers the count (a CI run: 30 of 31 counted, 93 missing).
  EXPECT_LE(r.final.propagator.invalid, r.stats.faults.imu_nonfinite);
  EXPECT_GE(r.final.propagator.invalid + r.final.propagator.decode.missing_packets,
            r.stats.faults.imu_nonfinite);
  EXPECT_TRUE(AllPosesFinite(r));
  EXPECT_GE(r.poses.size(), 1000u);
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
}

// Every DIFOP arrives with bit errors in its calibration: the damaged ones are refused and
// counted, the configured calibration stays, and tracking is unaffected.
TEST(RuntimeFaults, CorruptedDifopIsRefusedAndCounted) {
  LiveDrive drive = Drive(8.0, 149);
  drive.faults.difop_corrupt = true;
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kLidar);
  EXPECT_GE(r.stats.faults.difop_corrupted, 6u);
  // Eight flipped bits per packet: a packet whose flips all fall below 1° of change (about 1 in
  // 80) is indistinguishable from a calibration and adopted until the next DIFOP replaces it.
  EXPECT_GE(r.final.optimizer.lidar.info_errors + 2, r.stats.faults.difop_corrupted);
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
}

// No DIFOP at all: the configured rpm and calibration are used.
TEST(RuntimeFaults, MissingDifopUsesTheConfiguration) {
  LiveDrive drive = Drive(8.0, 150);
  drive.faults.difop_missing = true;
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kLidar);
  EXPECT_EQ(r.final.optimizer.lidar.info_packets, 0u);
  EXPECT_TRUE(r.ready);
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
}

// For 2 s every return reads 0.6 m (a covered lens): nothing to match, so the IMU carries the
// state and the health says so; nothing crashes or goes non-finite, and the estimate carries
// on (re-initializing if it must) once the view is clear.
TEST(RuntimeFaults, PointsAllAtOneRangeAreNotTracked) {
  LiveDrive drive = Drive(12.0, 151);
  drive.faults.lidar_one_range = {{6.0, 2.0}};
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kEstimator);
  EXPECT_GE(r.stats.faults.msop_one_range, 500u);
  EXPECT_TRUE(AllPosesFinite(r));
  if (test::kSanitized) {
    // What the sanitizers are for: the odd returns pass every stage without a memory or UB
    // report (checked above by running). The behaviour is not: a sanitized daemon sharing 2
    // cores with another test runs seconds behind its input (sweep_age_s above 2 s in CI
    // runs) and then re-initializes for that, not for the fault. The Release build checks it.
    return;
  }
  // Keyed by the sweeps' time, not the snapshots', in case the daemon runs behind its input.
  const auto blind = r.StatesOfSweepsBetween(6.5, 8.0);
  ASSERT_FALSE(blind.empty()) << "no health snapshot of the blind sweeps";
  bool not_tracking = false;
  for (const HealthSnapshot* h : blind) {
    not_tracking = not_tracking || h->optimizer.tracking != TrackingState::kTracking;
  }
  EXPECT_TRUE(not_tracking) << "the health must not claim LiDAR tracking on a blind sensor";
  EXPECT_GE(r.PosesBetween(6.3, 8.0), 400u);
  EXPECT_TRUE(Carried(r.final.optimizer.tracking)) << ToString(r.final.optimizer.tracking);
}

// The LiDAR never starts: never READY, the LiDAR status is an error, no pose is published.
TEST(RuntimeFaults, LidarThatNeverStartsIsReported) {
  LiveDrive drive = Drive(4.0, 152);
  drive.faults.lidar_silent = true;
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kLidar);
  EXPECT_FALSE(r.ready);
  EXPECT_TRUE(r.PublishedSaid(kLidar, "no packets"));
  EXPECT_EQ(r.final.optimizer.lidar.data_packets, 0u);
  EXPECT_EQ(r.final.optimizer.tracking, TrackingState::kInitializing);
}

// The IMU never sends a byte: never READY, the IMU status is an error, no pose is published.
TEST(RuntimeFaults, ImuThatNeverStartsIsReported) {
  LiveDrive drive = Drive(4.0, 153);
  drive.faults.imu_silent = true;
  const LiveDriveResult r = RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished(kImu);
  EXPECT_FALSE(r.ready);
  EXPECT_TRUE(r.PublishedSaid(kImu, "no samples"));
  EXPECT_EQ(r.final.propagator.samples, 0u);
  EXPECT_TRUE(r.poses.empty());
}

}  // namespace
}  // namespace swlio::daemon

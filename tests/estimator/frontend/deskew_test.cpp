// De-skew on simulated sweeps at 1.5 m/s and up to 60 °/s: with the poses at each point's own
// time, the points land on the true surfaces; without de-skew they do not.

#include "swlio/estimator/frontend/deskew.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "scenarios/sim_setup.h"
#include "sensors/imu_sim.h"
#include "sensors/lidar_sim.h"
#include "sim_imu_util.h"
#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_propagator.h"

namespace swlio::estimator {
namespace {

Eigen::Isometry3d TruePose(const sim::SimSetup& setup, int64_t t_ns) {
  const sim::Kinematics k = setup.trajectory->At(NsToSec(t_ns));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = k.R_world_body;
  T.translation() = k.p_world;
  return T;
}

/// One sweep (75 packets) starting at `t_s`, as a Scan in the LiDAR frame with each point's
/// time, plus each point's true world position.
Scan SweepAt(const sim::SimSetup& setup, double t_s, std::vector<Eigen::Vector3d>* truth) {
  sim::LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, 1);
  lidar.SkipTo(t_s);
  sim::SimPacket packet;
  std::vector<sim::SimReturn> returns;
  Scan scan;
  scan.t_start_ns = -1;
  int packets = 0;
  while (packets < 75 && lidar.Next(&packet, &returns)) {
    if (returns.empty() || NsToSec(returns.front().t_true_ns) < t_s) continue;
    ++packets;
    for (const sim::SimReturn& r : returns) {
      if (r.range_m <= 0.0) continue;
      if (scan.t_start_ns < 0) scan.t_start_ns = r.t_true_ns;
      LidarPoint p;
      p.xyz_m = sim::SimDecodedPoint(setup.lidar, r.channel, r.t_true_ns, r.range_m).cast<float>();
      p.dt_ns = r.t_true_ns - scan.t_start_ns;
      scan.t_end_ns = r.t_true_ns;
      scan.points.push_back(p);
      truth->push_back(r.p_world);
    }
  }
  return scan;
}

TEST(Deskew, PointsLandOnTheTrueSurfacesAtSpeed) {
  auto setup = sim::MakeSimSetup("aggressive", 8, 40.0);
  ASSERT_TRUE(setup);
  setup->lidar.range_sigma_m = 0.0;  // isolate the motion error from range noise
  setup->lidar.dropout = 0.0;
  PoseTrack track;  // one pose per 400 Hz IMU sample, as the propagator provides
  for (int64_t t = 0; t <= SecToNs(39.0); t += 2'500'000) track.Add(t, TruePose(*setup, t));

  size_t within = 0, total = 0, raw_far = 0;
  for (const double t_s : {6.3, 14.1, 22.7, 30.2}) {
    std::vector<Eigen::Vector3d> truth;
    const Scan scan = SweepAt(*setup, t_s, &truth);
    ASSERT_GT(scan.points.size(), 10'000u);
    std::vector<Eigen::Vector3d> deskewed;
    const DeskewResult r = Deskew(scan, track, setup->lidar.T_imu_lidar, &deskewed);
    EXPECT_EQ(r.uncovered, 0u);
    const Eigen::Isometry3d T_world_lidar_end =
        TruePose(*setup, scan.t_end_ns) * setup->lidar.T_imu_lidar;
    for (size_t i = 0; i < deskewed.size(); ++i) {
      const double err = (T_world_lidar_end * deskewed[i] - truth[i]).norm();
      within += err < 0.02 ? 1 : 0;
      const double raw =
          (T_world_lidar_end * scan.points[i].xyz_m.cast<double>() - truth[i]).norm();
      raw_far += raw > 0.05 ? 1 : 0;
      ++total;
    }
  }
  EXPECT_GT(static_cast<double>(within), 0.999 * static_cast<double>(total));
  EXPECT_GT(static_cast<double>(raw_far), 0.3 * static_cast<double>(total))
      << "without de-skew many points are off by more than 5 cm";
}

// As in the odometry: the track is the IMU propagated over the sweep (noisy samples with the
// simulator's biases, which the propagator does not know) from the true state at the sweep's
// start; the points are compared in the sweep-end frame of that same track.
TEST(Deskew, ImuPropagatedTrackKeepsPointsWithinTwoCentimetres) {
  auto setup = sim::MakeSimSetup("aggressive", 8, 40.0);
  ASSERT_TRUE(setup);
  setup->lidar.range_sigma_m = 0.0;
  setup->lidar.dropout = 0.0;
  const std::vector<ImuSample> imu =
      test::ToImuSamples(sim::SimulateImu(*setup->trajectory, setup->imu, 8));
  size_t within = 0, total = 0;
  double worst_rate = 0.0;
  for (const double t_s : {6.3, 14.1, 22.7, 30.2}) {
    std::vector<Eigen::Vector3d> truth;
    const Scan scan = SweepAt(*setup, t_s, &truth);
    ImuPropagator propagator(setup->imu.gravity_mps2);
    propagator.Reset(test::TrueState(*setup->trajectory, scan.t_start_ns));
    for (const ImuSample& s : imu) {
      if (s.t_ns > scan.t_end_ns) break;
      if (s.t_ns >= scan.t_start_ns - 2'500'000) propagator.Add(s);
      worst_rate = std::max(worst_rate, s.t_ns >= scan.t_start_ns ? s.gyro_radps.norm() : 0.0);
    }
    propagator.ExtrapolateTo(scan.t_end_ns);
    std::vector<Eigen::Vector3d> deskewed;
    ASSERT_EQ(Deskew(scan, propagator.track(), setup->lidar.T_imu_lidar, &deskewed).uncovered, 0u);
    const Eigen::Isometry3d T_world_lidar_end =
        TruePose(*setup, scan.t_end_ns) * setup->lidar.T_imu_lidar;
    for (size_t i = 0; i < deskewed.size(); ++i) {
      within += (T_world_lidar_end * deskewed[i] - truth[i]).norm() < 0.02 ? 1 : 0;
      ++total;
    }
  }
  EXPECT_GT(worst_rate, 0.7) << "the sweeps include a fast turn";
  EXPECT_GT(static_cast<double>(within), 0.99 * static_cast<double>(total));
}

TEST(Deskew, PointsOutsideTheTrackAreCountedNotMoved) {
  PoseTrack track;
  track.Add(100, Eigen::Isometry3d::Identity());
  track.Add(200, Eigen::Isometry3d::Identity());
  Scan scan;
  scan.t_start_ns = 150;
  scan.t_end_ns = 190;
  scan.points.resize(2);
  scan.points[0].xyz_m = Eigen::Vector3f(1, 2, 3);
  scan.points[1].dt_ns = 100;  // at 250: beyond the track
  std::vector<Eigen::Vector3d> out;
  const DeskewResult r = Deskew(scan, track, Eigen::Isometry3d::Identity(), &out);
  EXPECT_EQ(r.uncovered, 1u);
  EXPECT_TRUE(out[0].isApprox(Eigen::Vector3d(1, 2, 3)));
}

/// A track of `n` poses 2.5 ms apart turning at up to 2 rad/s about a wobbling axis, and a
/// sweep of `points` points spread over it (16 per 55.5 µs firing sequence, as the RS16).
struct TrackAndSweep {
  PoseTrack track;
  std::vector<Eigen::Isometry3d> poses;
  Scan scan;
};

TrackAndSweep Turning(int n, size_t points, uint32_t seed) {
  TrackAndSweep out;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d axis = Eigen::Vector3d(0.2 * unit(rng), 0.2 * unit(rng), 1.0);
    T.linear() = T.linear() *
                 Eigen::AngleAxisd(0.005 * (1.0 + unit(rng)), axis.normalized()).toRotationMatrix();
    T.translation() += Eigen::Vector3d(0.004, 0.001 * unit(rng), 0.0);
    out.poses.push_back(T);
    out.track.Add(int64_t{i} * 2'500'000, T);
  }
  out.scan.t_start_ns = 1'000'000;
  out.scan.t_end_ns = int64_t{n - 1} * 2'500'000 - 1'000'000;
  const int64_t span_ns = out.scan.t_end_ns - out.scan.t_start_ns;
  for (size_t i = 0; i < points; ++i) {
    LidarPoint p;
    p.xyz_m = Eigen::Vector3f(static_cast<float>(20.0 * unit(rng)),
                              static_cast<float>(20.0 * unit(rng)), static_cast<float>(unit(rng)));
    p.ring = static_cast<uint16_t>(i % 16);
    p.intensity = static_cast<float>(i % 256);
    p.dt_ns = std::min<int64_t>(
        span_ns, static_cast<int64_t>(i / 16) * 55'500 + static_cast<int64_t>(i % 16) * 3'470);
    out.scan.points.push_back(p);
  }
  return out;
}

// The track keeps each segment's dot product, angle and sine for its slerp: the interpolated
// pose must be Eigen's slerp to the last bit, anywhere in a segment and at its ends.
TEST(PoseTrack, InterpolationIsEigensSlerpToTheLastBit) {
  const TrackAndSweep ts = Turning(41, 0, 3);
  for (int64_t t = 0; t <= 40 * 2'500'000; t += 7'919) {
    Eigen::Isometry3d T;
    ASSERT_TRUE(ts.track.At(t, &T));
    const auto i = static_cast<size_t>(std::min<int64_t>(t / 2'500'000, 39));
    const double u = static_cast<double>(t - static_cast<int64_t>(i) * 2'500'000) / 2'500'000.0;
    const Eigen::Quaterniond qa = Eigen::Quaterniond(ts.poses[i].linear()).normalized();
    const Eigen::Quaterniond qb = Eigen::Quaterniond(ts.poses[i + 1].linear()).normalized();
    const Eigen::Matrix3d R = qa.slerp(u, qb).toRotationMatrix();
    ASSERT_EQ(T.linear(), R) << "t " << t;
  }
}

// DeskewScan (the window's) writes what Deskew does, rounded to float, beside the points'
// other fields, and a scan reused for the next sweep holds nothing of the last one.
TEST(Deskew, IntoAScanEqualsTheVectorFormAndReuseLeavesNothingBehind) {
  const TrackAndSweep big = Turning(41, 16'000, 5);
  const TrackAndSweep small = Turning(41, 9'000, 6);
  Scan reused;
  for (const TrackAndSweep* ts : {&big, &small}) {
    std::vector<Eigen::Vector3d> xyz;
    const DeskewResult a = Deskew(ts->scan, ts->track, Eigen::Isometry3d::Identity(), &xyz);
    const DeskewResult b = DeskewScan(ts->scan, ts->track, Eigen::Isometry3d::Identity(), &reused);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.uncovered, b.uncovered);
    ASSERT_EQ(reused.points.size(), ts->scan.points.size());
    EXPECT_EQ(reused.t_start_ns, ts->scan.t_start_ns);
    EXPECT_EQ(reused.t_end_ns, ts->scan.t_end_ns);
    for (size_t i = 0; i < xyz.size(); ++i) {
      ASSERT_EQ(reused.points[i].xyz_m, Eigen::Vector3f(xyz[i].cast<float>())) << i;
      ASSERT_EQ(reused.points[i].dt_ns, ts->scan.points[i].dt_ns);
      ASSERT_EQ(reused.points[i].ring, ts->scan.points[i].ring);
      ASSERT_EQ(reused.points[i].intensity, ts->scan.points[i].intensity);
    }
  }
}

}  // namespace
}  // namespace swlio::estimator

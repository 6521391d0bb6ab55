// The batch extrinsic calibration on the simulator's "aggressive" drive (turns and a slalom on
// a nearly flat site): IMU at 400 Hz from the simulator (noise, biases), LiDAR-odometry poses
// at 10 Hz from the true trajectory in a tilted odometry world, with noise; the guess 2° and
// 5 cm off the truth (the start).

#include "swlio/estimator/calibration/extrinsic_calibrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kDeg = std::numbers::pi / 180.0;

struct SimDrive {
  std::optional<sim::SimSetup> setup;
  std::vector<ImuSample> imu;
  std::vector<StampedLidarPose> poses;
};

/// Poses every 0.1 s over [t0, t0 + seconds] with the given noise, in a tilted, shifted world.
SimDrive MakeDrive(uint64_t seed,
                   double t0_s,
                   double seconds,
                   double position_m,
                   double rotation_rad,
                   const std::string& scenario = "aggressive") {
  SimDrive r;
  r.setup = sim::MakeSimSetup(scenario, seed, t0_s + seconds + 1.0);
  r.imu = test::ToImuSamples(sim::SimulateImu(*r.setup->trajectory, r.setup->imu, seed));
  Eigen::Isometry3d T_w0_world = Eigen::Isometry3d::Identity();
  T_w0_world.linear() = lie::QuatFromRpy(0.2, -0.15, 1.0).toRotationMatrix();
  T_w0_world.translation() = Vec3(3.0, -2.0, 1.0);
  std::mt19937 rng(static_cast<uint32_t>(seed));
  std::normal_distribution<double> n01;
  auto gauss3 = [&](double sigma) {
    Vec3 v;
    for (int i = 0; i < 3; ++i) v(i) = sigma * n01(rng);
    return v;
  };
  const int frames = static_cast<int>(std::lround(seconds * 10.0)) + 1;
  for (int k = 0; k < frames; ++k) {
    const int64_t t_ns = SecToNs(t0_s + 0.1 * k);
    StampedLidarPose p;
    p.t_ns = t_ns;
    p.T_w0_lidar = T_w0_world * test::TrueState(*r.setup->trajectory, t_ns).T_world_imu *
                   r.setup->lidar.T_imu_lidar;
    p.T_w0_lidar.translation() += gauss3(position_m);
    p.T_w0_lidar.linear() = p.T_w0_lidar.linear() * lie::Exp(gauss3(rotation_rad));
    r.poses.push_back(p);
  }
  return r;
}

/// The truth moved by dx dy (m) and 2° about an axis in each direction (1.155° per axis).
Eigen::Isometry3d Perturbed(const Eigen::Isometry3d& truth, double dx, double dy) {
  Eigen::Isometry3d g = truth;
  g.translation() += Vec3(dx, dy, 0.0);
  g.linear() = g.linear() * lie::Exp(Vec3::Constant(2.0 * kDeg / std::sqrt(3.0)));
  return g;
}

struct Error {
  double rotation_deg, translation_xy_m, translation_z_m;
};

Error Compare(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth) {
  const Vec3 dt = estimate.translation() - truth.translation();
  return {Eigen::AngleAxisd(truth.linear().transpose() * estimate.linear()).angle() / kDeg,
          dt.head<2>().norm(), std::abs(dt.z())};
}

/// The options for MakeDrive's 1 cm / 0.1° pose noise.
ExtrinsicCalibratorOptions PoseNoiseOptions() {
  ExtrinsicCalibratorOptions o;
  o.position_sigma_m = 0.01;
  o.rotation_sigma_rad = 0.1 * kDeg;
  return o;
}

// 30 s of driving from 2 s on (the robot sets off at about 1.2 s): 1 cm / 0.1° pose noise.
TEST(ExtrinsicCalibrator, ThirtySecondsOfDrivingRecoverTheExtrinsic) {
  const SimDrive run = MakeDrive(1, 2.0, 30.0, 0.01, 0.1 * kDeg);
  const Eigen::Isometry3d& truth = run.setup->lidar.T_imu_lidar;
  const Eigen::Isometry3d guess = Perturbed(truth, 0.035, -0.035);  // 5 cm
  ASSERT_GT(Compare(guess, truth).rotation_deg, 1.99);
  const ExtrinsicCalibratorOptions o = PoseNoiseOptions();
  const ExtrinsicCalibration c =
      CalibrateExtrinsic(EstimatorConfig{}, run.poses, run.imu, guess, o);
  ASSERT_TRUE(c.ok) << c.message;
  const Error e = Compare(c.T_imu_lidar, truth);
  RecordProperty("rotation_deg", std::to_string(e.rotation_deg));
  RecordProperty("translation_xy_m", std::to_string(e.translation_xy_m));
  EXPECT_LT(e.rotation_deg, 0.3);
  EXPECT_LT(e.translation_xy_m, 0.02);
  // The reported uncertainty covers the error (3σ) and the pose fit matches the noise.
  const double sigma_rot_deg = std::sqrt(c.covariance.bottomRightCorner<3, 3>().trace()) / kDeg;
  EXPECT_LT(e.rotation_deg, 3.0 * sigma_rot_deg + 0.02);
  EXPECT_LT(c.position_rms_m, 0.02);
  EXPECT_LT(c.rotation_rms_rad, 0.2 * kDeg);
}

// A planar drive turns about the vertical only: the lever arm along it is not observed, which
// the covariance says (its σ stays near the prior's) instead of inventing a value.
TEST(ExtrinsicCalibrator, PlanarDriveLeavesTheVerticalLeverArmAtItsPrior) {
  const SimDrive run = MakeDrive(2, 2.0, 30.0, 0.01, 0.1 * kDeg);
  const Eigen::Isometry3d& truth = run.setup->lidar.T_imu_lidar;
  const ExtrinsicCalibratorOptions o = PoseNoiseOptions();
  const ExtrinsicCalibration c =
      CalibrateExtrinsic(EstimatorConfig{}, run.poses, run.imu, Perturbed(truth, 0.0, 0.0), o);
  ASSERT_TRUE(c.ok) << c.message;
  // The vertical in the IMU frame (the IMU is mounted level).
  const double sigma_z = std::sqrt(c.covariance(2, 2));
  const double sigma_x = std::sqrt(c.covariance(0, 0));
  EXPECT_GT(sigma_z, 0.5 * o.extrinsic_prior_sigma_m) << "σ x " << sigma_x;
  EXPECT_LT(sigma_x, 0.2 * sigma_z);
}

// The calibration course (roll and pitch over cable covers) shows the vertical lever arm too.
TEST(ExtrinsicCalibrator, TheCalibrationCourseRecoversTheVerticalLeverArm) {
  for (const uint64_t seed : {1, 2, 3}) {
    const SimDrive run = MakeDrive(seed, 2.0, 30.0, 0.01, 0.1 * kDeg, "calibration");
    const Eigen::Isometry3d& truth = run.setup->lidar.T_imu_lidar;
    Eigen::Isometry3d guess = Perturbed(truth, 0.0289, 0.0289);
    guess.translation().z() += 0.0289;  // 5 cm and 2° off
    const ExtrinsicCalibration c =
        CalibrateExtrinsic(EstimatorConfig{}, run.poses, run.imu, guess, PoseNoiseOptions());
    ASSERT_TRUE(c.ok) << c.message;
    const Error e = Compare(c.T_imu_lidar, truth);
    std::printf("seed %d: %.3f deg, xy %.4f m, z %.4f m (sigma z %.4f m)\n", static_cast<int>(seed),
                e.rotation_deg, e.translation_xy_m, e.translation_z_m,
                std::sqrt(c.covariance(2, 2)));
    EXPECT_EQ(c.translation_directions, 3);
    EXPECT_LT(e.rotation_deg, 0.3);
    EXPECT_LT(std::hypot(e.translation_xy_m, e.translation_z_m), 0.02);
  }
}

/// The calibration course's poses with noise that the scans would leave: σ_along (m) along
/// each pose's LiDAR y axis (a road between walls), 2 mm across it, 0.05°; every 25th pose
/// 10 cm off along y (a registration gone wrong). With `hessian`, each pose carries the
/// registration Hessian that noise corresponds to (σ_point 2 cm, the option's default).
SimDrive CorridorDrive(uint64_t seed, double sigma_along_m, bool hessian) {
  SimDrive run = MakeDrive(seed, 2.0, 30.0, 0.0, 0.0, "calibration");
  std::mt19937 rng(static_cast<uint32_t>(seed) + 7u);
  std::normal_distribution<double> n01;
  const Eigen::Vector3d sigma_m(0.002, sigma_along_m, 0.002);
  const double sigma_rad = 0.05 * kDeg;
  for (size_t k = 0; k < run.poses.size(); ++k) {
    StampedLidarPose& p = run.poses[k];
    Vec3 rho(sigma_m.x() * n01(rng), sigma_m.y() * n01(rng), sigma_m.z() * n01(rng));
    if (k % 25 == 12) rho.y() += 0.10;
    const Vec3 phi(sigma_rad * n01(rng), sigma_rad * n01(rng), sigma_rad * n01(rng));
    p.T_w0_lidar.translation() += p.T_w0_lidar.linear() * rho;
    p.T_w0_lidar.linear() = p.T_w0_lidar.linear() * lie::Exp(phi);
    if (!hessian) continue;
    Eigen::Matrix<double, 6, 1> information;
    information << sigma_m.cwiseInverse().cwiseAbs2(),
        Vec3::Constant(1.0 / (sigma_rad * sigma_rad));
    p.hessian = (0.02 * 0.02 * information).asDiagonal();
  }
  return run;
}

// Weighting each pose by its registration Hessian (and bounding a wrong one's pull) keeps the
// 2 cm on poses whose error lies mostly along one axis; the same poses with one σ for all
// directions do worse.
TEST(ExtrinsicCalibrator, PosesAreWeighedByTheirRegistrationHessian) {
  for (const uint64_t seed : {1, 2}) {
    const SimDrive weighted = CorridorDrive(seed, 0.03, true);
    const SimDrive plain = CorridorDrive(seed, 0.03, false);
    const Eigen::Isometry3d& truth = weighted.setup->lidar.T_imu_lidar;
    Eigen::Isometry3d guess = Perturbed(truth, 0.0289, -0.0289);
    guess.translation().z() += 0.0289;  // 5 cm and 2° off
    ExtrinsicCalibratorOptions o;
    o.position_sigma_m = 0.03 / std::sqrt(3.0);  // the rms per axis, for the plain poses
    o.rotation_sigma_rad = 0.05 * kDeg;
    const ExtrinsicCalibration a =
        CalibrateExtrinsic(EstimatorConfig{}, weighted.poses, weighted.imu, guess, o);
    const ExtrinsicCalibration b =
        CalibrateExtrinsic(EstimatorConfig{}, plain.poses, plain.imu, guess, o);
    ASSERT_TRUE(a.ok) << a.message;
    ASSERT_TRUE(b.ok) << b.message;
    const Error ea = Compare(a.T_imu_lidar, truth), eb = Compare(b.T_imu_lidar, truth);
    const double da = std::hypot(ea.translation_xy_m, ea.translation_z_m);
    const double db = std::hypot(eb.translation_xy_m, eb.translation_z_m);
    std::printf("seed %d: with Hessians %.4f m %.3f deg, without %.4f m %.3f deg\n",
                static_cast<int>(seed), da, ea.rotation_deg, db, eb.rotation_deg);
    EXPECT_EQ(a.translation_directions, 3);
    EXPECT_LT(da, 0.02);
    EXPECT_LT(ea.rotation_deg, 0.3);
    EXPECT_LT(da, db);
  }
}

TEST(ExtrinsicCalibrator, TooFewPosesIsReportedNotSolved) {
  const SimDrive run = MakeDrive(1, 2.0, 0.2, 0.01, 0.1 * kDeg);
  const ExtrinsicCalibration c =
      CalibrateExtrinsic(EstimatorConfig{}, run.poses, run.imu, run.setup->lidar.T_imu_lidar);
  EXPECT_FALSE(c.ok);
  EXPECT_FALSE(c.message.empty());
}

}  // namespace
}  // namespace swlio::estimator

// Chassis vibration (scenarios/chassis_vibration.h): its magnitude standing and driving, its
// band, and kinematics that stay consistent (the IMU measures the motion the LiDAR is cast
// from).

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <optional>

#include "disturb/apply_disturbances.h"
#include "disturb/disturbance_manifest.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/lie.h"

namespace swlio::sim {
namespace {

/// Vector RMS of the acceleration the vibration adds over [t0, t0 + 2 s] at 400 Hz, and the
/// share of its power in 15–80 Hz (DFT at 0.5 Hz steps).
void VibrationStats(
    const SimSetup& vib, const SimSetup& calm, double t0, double* rms, double* in_band) {
  std::vector<Eigen::Vector3d> a;
  for (int k = 0; k < 800; ++k) {
    const double t = t0 + k / 400.0;
    a.push_back(vib.trajectory->At(t).a_world - calm.trajectory->At(t).a_world);
  }
  double sum = 0.0;
  for (const auto& x : a) sum += x.squaredNorm();
  *rms = std::sqrt(sum / static_cast<double>(a.size()));
  double band = 0.0, all = 0.0;
  for (int bin = 1; bin < 400; ++bin) {
    const double hz = bin * 0.5;
    Eigen::Vector3cd X = Eigen::Vector3cd::Zero();
    for (size_t k = 0; k < a.size(); ++k) {
      X += a[k].cast<std::complex<double>>() *
           std::polar(1.0, -2.0 * M_PI * bin * static_cast<double>(k) / 800.0);
    }
    const double p = X.squaredNorm();
    all += p;
    if (hz >= 15.0 && hz <= 80.0) band += p;
  }
  *in_band = band / all;
}

TEST(SimVibration, MagnitudeStandingAndDrivingAndItsBand) {
  auto calm = MakeSimSetup("short", 3, 30.0);
  auto vib = MakeSimSetup("short", 3, 30.0);
  DisturbanceOverrides rms;
  rms.vibration_rest_rms_mps2 = 0.8;
  rms.vibration_drive_rms_mps2 = 1.8;
  ApplyDisturbances(&*vib, *ParseDisturbanceList("vibration", nullptr), rms);
  double rest = 0.0, drive = 0.0, band_rest = 0.0, band_drive = 0.0;
  VibrationStats(*vib, *calm, 0.0, &rest, &band_rest);  // standing for the first 2 s
  // Cruising at 1.2 m/s on short: the terrain part at 1.2 × its 1 m/s amplitude.
  VibrationStats(*vib, *calm, 15.0, &drive, &band_drive);
  const double expected_drive = std::sqrt(0.64 + 1.44 * (1.8 * 1.8 - 0.64));
  EXPECT_NEAR(rest, 0.8, 0.12);
  EXPECT_NEAR(drive, expected_drive, 0.25 * expected_drive);
  EXPECT_GT(band_rest, 0.99);
  EXPECT_GT(band_drive, 0.97);
  EXPECT_NE(DisturbanceManifestBlock(*vib).find("vibration_rest_rms_mps2: 0.8"), std::string::npos);
}

// --vibration-seed: the same drive under another vibration of the same magnitude. Its tones
// change, its RMS does not; the drive's own seed as the vibration seed changes nothing.
TEST(SimVibration, AnotherSeedDrawsOtherTonesOfTheSameMagnitude) {
  auto calm = MakeSimSetup("short", 3, 30.0);
  auto shaken = [](std::optional<uint64_t> vibration_seed) {
    auto setup = MakeSimSetup("short", 3, 30.0);
    DisturbanceOverrides o;
    o.vibration_seed = vibration_seed;
    ApplyDisturbances(&*setup, *ParseDisturbanceList("vibration", nullptr), o);
    return setup;
  };
  const auto drawn = shaken(std::nullopt), same = shaken(3), other = shaken(77);
  const ChassisVibration& v_drawn = *drawn->trajectory->vibration();
  const ChassisVibration& v_other = *other->trajectory->vibration();
  EXPECT_EQ(v_other.spec().rest_rms_mps2, v_drawn.spec().rest_rms_mps2);  // from the drive's seed
  EXPECT_EQ(v_other.spec().drive_rms_mps2, v_drawn.spec().drive_rms_mps2);
  EXPECT_NE(v_other.MotorFrequenciesHz(), v_drawn.MotorFrequenciesHz());
  EXPECT_EQ(same->trajectory->vibration()->MotorFrequenciesHz(), v_drawn.MotorFrequenciesHz());
  double rms_drawn = 0.0, rms_other = 0.0, band = 0.0;
  VibrationStats(*drawn, *calm, 15.0, &rms_drawn, &band);
  VibrationStats(*other, *calm, 15.0, &rms_other, &band);
  EXPECT_NEAR(rms_other, rms_drawn, 0.2 * rms_drawn);
  double largest_difference_mps2 = 0.0;
  for (int k = 0; k < 400; ++k) {
    const double t = 15.0 + k / 400.0;
    largest_difference_mps2 =
        std::max(largest_difference_mps2,
                 (other->trajectory->At(t).a_world - drawn->trajectory->At(t).a_world).norm());
    EXPECT_EQ(same->trajectory->At(t).a_world, drawn->trajectory->At(t).a_world);
  }
  EXPECT_GT(largest_difference_mps2, 0.5 * rms_drawn);
  EXPECT_NE(DisturbanceManifestBlock(*other).find("vibration_seed: 77"), std::string::npos);
  EXPECT_NE(DisturbanceManifestBlock(*drawn).find("vibration_seed: 3"), std::string::npos);
}

/// Velocity, acceleration and body rate with the vibration are the derivatives of the pose.
TEST(SimVibration, KinematicsAreConsistent) {
  auto vib = MakeSimSetup("short", 5, 30.0);
  ApplyDisturbances(&*vib, *ParseDisturbanceList("vibration", nullptr));
  const Trajectory& tr = *vib->trajectory;
  const double h = 1e-5;
  for (double t : {1.0, 6.3, 12.7, 20.1}) {
    const Kinematics k = tr.At(t), km = tr.At(t - h), kp = tr.At(t + h);
    const Eigen::Vector3d v_fd = (kp.p_world - km.p_world) / (2 * h);
    const Eigen::Vector3d a_fd = (kp.v_world - km.v_world) / (2 * h);
    const Eigen::Vector3d w_fd = lie::Log(km.R_world_body.transpose() * kp.R_world_body) / (2 * h);
    EXPECT_LT((v_fd - k.v_world).norm(), 1e-5) << t;
    EXPECT_LT((a_fd - k.a_world).norm(), 2e-3) << t;  // the left-out g'' term and rounding
    EXPECT_LT((w_fd - k.omega_body).norm(), 1e-4) << t;
  }
}

}  // namespace
}  // namespace swlio::sim

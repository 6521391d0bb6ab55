// GNSS position factor (gnss_factor.h) and the map-to-ENU alignment fit (gnss_associator.h).

#include "swlio/estimator/gnss/gnss_factor.h"

#include <gtest/gtest.h>

#include <random>

#include "jacobian_check.h"
#include "swlio/core/lie.h"
#include "swlio/estimator/gnss/gnss_associator.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

std::vector<double> PoseBlock(const Vec3& p, const Vec3& rotation_vector) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::Exp(rotation_vector);
  T.translation() = p;
  std::vector<double> x(kPoseSize);
  PoseToParameters(T, x.data());
  return x;
}

TEST(GnssPositionFactor, ResidualThroughAlignmentAndLeverArm) {
  const Vec3 b(-0.2, 0.1, 0.5);
  const std::vector<double> pose = PoseBlock({3.0, 4.0, 0.2}, {0.0, 0.0, 0.5});
  const std::vector<double> align = {0.3, 100.0, -50.0, 2.0};
  const Eigen::Isometry3d T_enu_map = EnuFromAlignment(align.data());
  const Vec3 antenna_enu = T_enu_map * (PoseFromParameters(pose.data()) * b);
  auto f = GnssPositionFactor::Create(b, antenna_enu + Vec3(1.0, 0.0, -3.0), 0.5, 1.5);
  ASSERT_NE(f, nullptr);
  const double* blocks[2] = {pose.data(), align.data()};
  Vec3 r;
  ASSERT_TRUE(f->Evaluate(blocks, r.data(), nullptr));
  EXPECT_NEAR(r.x(), -2.0, 1e-9);  // 1 m east at σ_h 0.5
  EXPECT_NEAR(r.y(), 0.0, 1e-9);
  EXPECT_NEAR(r.z(), 2.0, 1e-9);  // 3 m low at σ_v 1.5
  EXPECT_NEAR(f->Chi2(pose.data(), align.data()), 8.0, 1e-9);
}

TEST(GnssPositionFactor, JacobiansMatchNumeric) {
  auto f = GnssPositionFactor::Create({-0.2, 0.1, 0.5}, {90.0, -40.0, 3.0}, 0.8, 1.6);
  ASSERT_NE(f, nullptr);
  const PoseManifold pose;
  const test::JacobianErrors e = test::CheckJacobians(
      *f, {PoseBlock({3.0, 4.0, 0.2}, {0.1, -0.05, 0.5}), {0.3, 100.0, -50.0, 2.0}},
      {&pose, nullptr});
  EXPECT_LT(e.Worst(), 1e-7);
}

TEST(GnssPositionFactor, RefusesBadInput) {
  EXPECT_EQ(GnssPositionFactor::Create(Vec3::Zero(), Vec3(NAN, 0, 0), 1.0, 1.0), nullptr);
  EXPECT_EQ(GnssPositionFactor::Create(Vec3::Zero(), Vec3::Zero(), 0.0, 1.0), nullptr);
  EXPECT_EQ(GnssPositionFactor::Create(Vec3::Zero(), Vec3::Zero(), 1.0, -1.0), nullptr);
}

TEST(FitEnuAlignment, RecoversYawAndTranslation) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.3);
  Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity();
  T_true.linear() = Eigen::AngleAxisd(-2.2, Vec3::UnitZ()).toRotationMatrix();
  T_true.translation() = Vec3(-350.0, 1200.0, 4.0);
  std::vector<Vec3> map_m, enu_m;
  for (int i = 0; i < 60; ++i) {  // an L: 40 m along x, then 20 m along y
    const Vec3 p = i < 40 ? Vec3(i, 0.0, 0.1 * i) : Vec3(40.0, i - 40.0, 4.0);
    map_m.push_back(p);
    enu_m.push_back(T_true * p + Vec3(noise(rng), noise(rng), noise(rng)));
  }
  const Eigen::Isometry3d T = FitEnuAlignment(map_m, enu_m);
  EXPECT_LT(Eigen::AngleAxisd(T.linear().transpose() * T_true.linear()).angle(), 0.02);
  EXPECT_LT((T.translation() - T_true.translation()).norm(), 0.5);
  EXPECT_NEAR(T.linear()(2, 2), 1.0, 1e-12);  // yaw only
}

}  // namespace
}  // namespace swlio::estimator

// Pose hints as operators send them (pose_hint.h): rviz2's /initialpose with its covariance,
// swlioctl relocalize's numbers, and what is refused; the base_link hint turned into the IMU's.
#include "swlio/daemon/pipeline/pose_hint.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

ipc::PoseWithCovarianceStamped Rviz(double x, double y, double yaw) {
  ipc::PoseWithCovarianceStamped m;
  m.frame_id = "map";
  m.pose.position_m = {x, y, 0.0};
  m.pose.orientation_xyzw = {0.0, 0.0, std::sin(yaw / 2), std::cos(yaw / 2)};
  m.covariance[0] = 0.25;
  m.covariance[7] = 0.25;
  m.covariance[35] = 0.06853891945200942;
  return m;
}

TEST(PoseHint, InitialPoseAsRvizSendsIt) {
  std::string error;
  const auto h = HintFromInitialPose(Rviz(3.0, -4.0, 2.0), "map", &error);
  ASSERT_TRUE(h.has_value()) << error;
  EXPECT_DOUBLE_EQ(h->x_m, 3.0);
  EXPECT_DOUBLE_EQ(h->y_m, -4.0);
  EXPECT_NEAR(h->yaw_rad, 2.0, 1e-12);
  EXPECT_NEAR(h->sigma_xy_m, 0.5, 1e-12);
  EXPECT_NEAR(h->sigma_yaw_rad, 0.2618, 1e-4);
  EXPECT_EQ(h->source, "/initialpose");
  // No covariance: the defaults; a larger y variance wins.
  ipc::PoseWithCovarianceStamped m = Rviz(0, 0, 0);
  m.covariance = {};
  m.covariance[7] = 4.0;
  m.covariance[35] = std::numeric_limits<double>::quiet_NaN();
  const auto d = HintFromInitialPose(m, "map", &error);
  ASSERT_TRUE(d.has_value());
  EXPECT_DOUBLE_EQ(d->sigma_xy_m, 2.0);
  EXPECT_DOUBLE_EQ(d->sigma_yaw_rad, PoseHint{}.sigma_yaw_rad);
}

TEST(PoseHint, InitialPoseInAnotherFrameOrNotAPoseIsRefused) {
  std::string error;
  ipc::PoseWithCovarianceStamped m = Rviz(1, 2, 0);
  m.frame_id = "odom";
  EXPECT_FALSE(HintFromInitialPose(m, "map", &error).has_value());
  EXPECT_THAT(error, HasSubstr("frame 'odom' is not the map frame 'map'"));
  m = Rviz(1, 2, 0);
  m.pose.orientation_xyzw = {0, 0, 0, 0};
  EXPECT_FALSE(HintFromInitialPose(m, "map", &error).has_value());
  m = Rviz(std::numeric_limits<double>::infinity(), 2, 0);
  EXPECT_FALSE(HintFromInitialPose(m, "map", &error).has_value());
  EXPECT_THAT(error, HasSubstr("not finite"));
}

TEST(PoseHint, RelocalizeArgument) {
  std::string error;
  const auto h = HintFromArgument("12.5 -3 90", &error);
  ASSERT_TRUE(h.has_value()) << error;
  EXPECT_DOUBLE_EQ(h->x_m, 12.5);
  EXPECT_DOUBLE_EQ(h->y_m, -3.0);
  EXPECT_NEAR(h->yaw_rad, kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(h->sigma_xy_m, 0.5);
  const auto s = HintFromArgument("0 0 270 2", &error);
  ASSERT_TRUE(s.has_value()) << error;
  EXPECT_NEAR(s->yaw_rad, -kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(s->sigma_xy_m, 2.0);
  for (const char* bad :
       {"", "1 2", "1 2 x", "1 2 3 0", "1 2 3 -1", "1 2 3 1 5", "nan 2 3", "1 2 3 4 extra"}) {
    EXPECT_FALSE(HintFromArgument(bad, &error).has_value()) << "'" << bad << "'";
  }
}

TEST(PoseHint, TheBaseHintBecomesTheImusPose) {
  PoseHint h;
  h.x_m = 10.0;
  h.y_m = 5.0;
  h.yaw_rad = kPi / 2;  // base facing +y
  Eigen::Isometry3d T_base_imu = Eigen::Isometry3d::Identity();
  T_base_imu.translation() << 0.3, 0.0, 0.5;  // IMU 0.3 m ahead of the base
  T_base_imu.linear() =
      Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitZ()).matrix();  // mounted backwards
  const estimator::LocalizationHint imu = ImuHint(h, T_base_imu);
  EXPECT_NEAR(imu.x_m, 10.0, 1e-12);
  EXPECT_NEAR(imu.y_m, 5.3, 1e-12);
  EXPECT_NEAR(std::abs(imu.yaw_rad), 3 * kPi / 2 - kPi, 1e-12);  // facing -y
  EXPECT_LT(imu.yaw_rad, 0.0);
}

}  // namespace
}  // namespace swlio::daemon

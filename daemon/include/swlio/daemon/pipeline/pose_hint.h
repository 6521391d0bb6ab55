#pragma once
/// @file
/// An operator's "the robot is here" (issue 34): rviz2's "2D Pose Estimate" on /initialpose
/// (geometry_msgs/PoseWithCovarianceStamped, base_link in the map frame) or `swlioctl
/// relocalize x y yaw [sigma]`. The localization thread turns it into an IMU hint for
/// MapLocalizer::ApplyHint and reports the outcome as one sentence (log, health, swlioctl).

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>

#include "swlio/daemon/control/pending_command.h"
#include "swlio/estimator/map/map_localizer.h"
#include "swlio/ipc/messages.h"

namespace swlio::daemon {

struct PoseHint {
  std::string source;  ///< "/initialpose" or "swlioctl"
  double x_m = 0.0;    ///< base_link in the map frame
  double y_m = 0.0;
  double yaw_rad = 0.0;
  /// 1σ; rviz2 sends 0.5 m and 0.26 rad (x, y and yaw variances 0.25 and 0.0685).
  double sigma_xy_m = 0.5;
  double sigma_yaw_rad = 0.26;
  /// swlioctl: answered once the hint was applied; null for /initialpose.
  std::shared_ptr<PendingCommand> command;
};

/// rviz2's /initialpose in the map frame `map_frame`: std::nullopt with *error (a sentence) when
/// the frame is another, the pose not finite, or the orientation not a rotation. σ from the
/// covariance (the larger of x and y; yaw's), defaults where it gives none.
std::optional<PoseHint> HintFromInitialPose(const ipc::PoseWithCovarianceStamped& message,
                                            const std::string& map_frame,
                                            std::string* error);

/// swlioctl relocalize's argument "x y yaw_deg [sigma_m]"; std::nullopt with *error.
std::optional<PoseHint> HintFromArgument(const std::string& argument, std::string* error);

/// The IMU's hint for a base_link hint (T_base_imu: the IMU in the base frame).
estimator::LocalizationHint ImuHint(const PoseHint& hint, const Eigen::Isometry3d& T_base_imu);

/// One sentence: where it localized, or why the hint was refused.
std::string DescribeHint(const PoseHint& hint, const estimator::HintOutcome& outcome);

}  // namespace swlio::daemon

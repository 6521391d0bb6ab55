#pragma once
/// @file
/// Turns GNSS fixes into pose-graph observations (gnss_factor.h): gates them (fix type,
/// accuracy, rate), converts them into the local ENU frame (geodetic.h; the configured origin,
/// or the first accepted fix), and places each on the keyframe node at or before its time: the
/// odometry between that node and the fix's time (interpolated between the keyframes around
/// it) moves the lever arm, so the observation is the antenna's position in the node's IMU
/// frame at the fix's time. A fix waits until the odometry has passed its time.
/// Pure library: no clock, no threads.

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "swlio/core/geodetic.h"
#include "swlio/core/types.h"
#include "swlio/estimator/common/keyframe_cloud.h"
#include "swlio/estimator/frontend/deskew.h"  // PoseTrack
#include "swlio/estimator/gnss/gnss_config.h"

namespace swlio::estimator {

struct GnssObservation {
  int64_t t_ns = 0;
  size_t node = 0;
  Eigen::Vector3d antenna_imu_m = Eigen::Vector3d::Zero();  ///< in the node's IMU frame
  Eigen::Vector3d fix_enu_m = Eigen::Vector3d::Zero();
  double sigma_h_m = 1.0;
  double sigma_v_m = 1.0;
  /// σ's inflation for the errors' correlation (gnss_config.h); the innovation gate undoes it:
  /// a fix is judged against the receiver's own accuracy.
  double inflation = 1.0;
};

struct GnssStats {
  size_t fixes = 0;         ///< offered
  size_t bad_quality = 0;   ///< fix type, accuracy or a non-finite value
  size_t rate_limited = 0;  ///< within min_interval_s of the last one taken
  size_t unplaced = 0;      ///< no odometry or node around its time
  size_t observations = 0;  ///< placed on a node
};

class GnssAssociator {
 public:
  explicit GnssAssociator(const GnssConfig& config);

  void AddFix(const GnssFix& fix);
  /// The odometry's pose (T_odom_imu, time order), at least at every keyframe.
  void AddOdometry(int64_t t_ns, const Eigen::Isometry3d& T_odom_imu);
  /// Observations of the waiting fixes the odometry now covers, on `nodes` (time order, poses
  /// in the same odometry frame).
  std::vector<GnssObservation> Take(std::span<const KeyframeCloud> nodes);

  /// The local ENU frame (none before the origin is known).
  const std::optional<LocalEnu>& enu() const { return enu_; }
  std::optional<Geodetic> origin() const { return origin_; }
  const GnssStats& stats() const { return stats_; }

 private:
  struct Pending {
    int64_t t_ns = 0;
    Eigen::Vector3d enu_m;
    double sigma_h_m = 1.0, sigma_v_m = 1.0;
  };
  bool Accept(const GnssFix& fix);

  GnssConfig config_;
  double inflation_ = 1.0;  ///< of σ, for the errors' correlation (gnss_config.h)
  std::optional<Geodetic> origin_;
  std::optional<LocalEnu> enu_;
  std::deque<Pending> pending_;
  PoseTrack odometry_;  ///< T_odom_imu, the last kKeepOdometryNs
  int64_t last_taken_t_ns_ = 0;
  bool taken_any_ = false;
  GnssStats stats_;
};

/// The 4-DoF T_enu_map (yaw about z, translation) that best maps `map_m` onto `enu_m` (least
/// squares; the closed form of the 2-D rotation on the centred horizontal coordinates).
Eigen::Isometry3d FitEnuAlignment(std::span<const Eigen::Vector3d> map_m,
                                  std::span<const Eigen::Vector3d> enu_m);

}  // namespace swlio::estimator

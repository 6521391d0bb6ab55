#pragma once
/// @file
/// Options of the GNSS position factor in the pose graph (gnss_factor.h, gnss_associator.h),
/// apart from them so that configuration code does not pull in Ceres.

#include <Eigen/Core>
#include <limits>

#include "swlio/core/config_issue.h"

namespace swlio::estimator {

struct GnssConfig {
  /// Off by default: the MTi-G-710's own GNSS items (GnssPvtData) on the graph's nodes.
  bool enabled = false;
  /// Origin of the local ENU frame the fixes are expressed in (WGS-84, ellipsoidal height).
  /// Not set (NaN): the first accepted fix.
  double origin_lat_deg = std::numeric_limits<double>::quiet_NaN();
  double origin_lon_deg = std::numeric_limits<double>::quiet_NaN();
  double origin_height_m = std::numeric_limits<double>::quiet_NaN();
  /// The antenna's phase centre in the IMU frame (the lever arm).
  Eigen::Vector3d antenna_imu_m = Eigen::Vector3d::Zero();
  /// Fixes used: at least this u-blox fixType (3: 3D) with a horizontal accuracy below this.
  int min_fix_type = 3;
  double max_h_acc_m = 10.0;
  /// σ of a fix = max(min_sigma_m, sigma_scale × the receiver's own accuracy).
  double sigma_scale = 1.0;
  double min_sigma_m = 0.05;
  /// At most one fix per this interval: a receiver's errors are correlated over tens of
  /// seconds, so 4 Hz fixes are not independent and would pull the map along their wander.
  double min_interval_s = 1.0;
  /// A fix is placed on the odometry between the two keyframes around it, at most this far
  /// apart (else it is dropped).
  double max_interpolation_s = 2.0;
  /// The map-to-ENU yaw is fitted once the fixes span this much horizontally.
  double align_min_distance_m = 20.0;
  /// The graph is optimized after this many new GNSS edges.
  int optimize_every_fixes = 5;
  /// Huber scale on the whitened residual, and the χ² bound (3 DoF; 16.27 is its 99.9 % point)
  /// above which an edge is switched off as an outlier.
  double kernel = 3.0;
  double max_chi2 = 16.27;

  bool has_origin() const { return origin_lat_deg == origin_lat_deg; }  // not NaN
  ConfigIssues Validate() const;
};

}  // namespace swlio::estimator

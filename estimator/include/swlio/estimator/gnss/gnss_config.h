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
  /// σ of a fix = max(min_sigma_m, sigma_scale × the receiver's own accuracy) ×
  /// √(correlation_time_s / min_interval_s) (at least ×1).
  double sigma_scale = 1.0;
  double min_sigma_m = 0.05;
  /// At most one fix per this interval.
  double min_interval_s = 1.0;
  /// How long a receiver's error stays correlated (multipath, atmosphere, orbit: tens of
  /// seconds for an SPS/SBAS receiver). The fixes within it are not independent: weighted as
  /// if they were, they outweigh the odometry and drag the map along their slow wander
  /// (measured on loop943: APE with loop closure 0.105 → 0.41 m). So each one's σ is inflated
  /// for one correlation time of fixes to carry the information of one. 0: no inflation.
  double correlation_time_s = 30.0;
  /// A fix is placed on the odometry between the two keyframes around it, at most this far
  /// apart (else it is dropped).
  double max_interpolation_s = 2.0;
  /// The map-to-ENU yaw is fitted once the fixes span this much horizontally.
  double align_min_distance_m = 20.0;
  /// The graph is optimized after this many new GNSS edges.
  int optimize_every_fixes = 5;
  /// Innovation gate before a fix enters the graph (after the alignment): its distance from
  /// where the graph puts the antenna, in the receiver's own σ (without the inflation), must
  /// stay below this many times max(1, the median of the last accepted ones): a multipath jump
  /// with an optimistic accuracy stands out against the fixes around it, a slow wander or an
  /// odometry drift does not. After `gate_reset_after` refusals in a row the next fix is taken.
  double gate_sigmas = 4.0;
  int gate_reset_after = 10;
  /// Huber scale on the whitened residual, and the χ² bound (3 DoF; 16.27 is its 99.9 % point)
  /// above which an edge is switched off after a solve (the gate's second line).
  double kernel = 3.0;
  double max_chi2 = 16.27;

  bool has_origin() const { return origin_lat_deg == origin_lat_deg; }  // not NaN
  ConfigIssues Validate() const;
};

}  // namespace swlio::estimator

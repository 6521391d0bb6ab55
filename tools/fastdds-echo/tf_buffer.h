#pragma once
/// @file
/// A small time-indexed transform buffer, as a ROS 2 node's tf2 `BufferCore` keeps one, for the
/// one chain swlio publishes: map → odom → base_link, plus the static transforms under it.
///
/// Lookups follow what tf2 would answer for swlio's /tf:
/// - odom → base_link goes out with every pose, stamped like it: looked up at exactly the stamp
///   (tf2 interpolates between neighbours; at an exact stamp that is the sample itself).
/// - map → odom goes out when it changes and every `ipc.map_odom_period_s`, each sample valid for
///   the poses up to the next: the latest at or before the stamp (what tf2's interpolation
///   between two samples would give for a transform that holds until it changes).
/// - static transforms (/tf_static) hold at every time.
///
/// `T_a_b` maps points from frame b to frame a (a TransformStamped with header.frame_id a and
/// child_frame_id b). Times are ROS time in ns. Capacity is bounded: the oldest entries go.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace swlio::tools::fastdds_echo {

/// One odom → base_link sample and how far it moved from the previous one in stamp order.
struct OdomSample {
  Eigen::Isometry3d T_odom_base = Eigen::Isometry3d::Identity();
  int64_t age_ns = 0;      ///< receiver's CLOCK_REALTIME at take − stamp
  bool has_step = false;   ///< false for the first sample
  double step_m = 0.0;     ///< translation from the previous sample
  double step_deg = 0.0;   ///< rotation angle from the previous sample
  int64_t step_dt_ns = 0;  ///< stamp difference to the previous sample
};

/// A static transform as received on /tf_static.
struct StaticTransform {
  std::string parent;
  std::string child;
  Eigen::Isometry3d T_parent_child = Eigen::Isometry3d::Identity();
};

class TfBuffer {
 public:
  /// `capacity`: entries kept per dynamic transform (2000 = 5 s of poses at 400 Hz).
  explicit TfBuffer(size_t capacity = 2000) : capacity_(capacity) {}

  /// Adds map → odom at `stamp_ns` (a repeated stamp replaces the entry).
  void AddMapOdom(int64_t stamp_ns, const Eigen::Isometry3d& T_map_odom);
  /// Adds odom → base_link at `stamp_ns`; its step is measured from the newest earlier sample.
  void AddOdomBase(int64_t stamp_ns, const Eigen::Isometry3d& T_odom_base, int64_t age_ns);
  /// Replaces the static transforms (a /tf_static sample holds all of them, as tf2_ros's
  /// StaticTransformBroadcaster sends them).
  void SetStatic(std::vector<StaticTransform> transforms) { static_ = std::move(transforms); }

  /// The latest map → odom at or before `stamp_ns`, with its stamp.
  std::optional<std::pair<int64_t, Eigen::Isometry3d>> MapOdomAt(int64_t stamp_ns) const;
  /// odom → base_link at exactly `stamp_ns`.
  const OdomSample* OdomBaseAt(int64_t stamp_ns) const;
  /// The newest odom → base_link stamp (0 before any).
  int64_t newest_odom_stamp_ns() const {
    return odom_base_.empty() ? 0 : odom_base_.rbegin()->first;
  }
  const std::vector<StaticTransform>& statics() const { return static_; }

 private:
  size_t capacity_;
  std::map<int64_t, Eigen::Isometry3d> map_odom_;
  std::map<int64_t, OdomSample> odom_base_;
  std::vector<StaticTransform> static_;
};

/// The rotation angle between two orientations, degrees.
double AngleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace swlio::tools::fastdds_echo

#pragma once
/// @file
/// `swlio-fastdds-echo --tf-check`: what a ROS 2 consumer (a tf2 listener beside a pose
/// subscriber) makes of swlio's outputs. For every map-frame pose it composes
/// T_map_base = T_map_odom (latest at or before the pose's stamp) · T_odom_base (at the stamp)
/// from /tf, once /tf_static has placed the sensor frames under base_link, and prints how far
/// that is from the published pose; with it the odom → base_link step from the previous sample
/// and the age of every stamp on the receiver's CLOCK_REALTIME. Pure: the caller passes the
/// samples (converted from Fast DDS types) and its clock readings.
///
/// Lines (one per event; `key=value` tokens after the first word, numbers in %.17g):
///
///   tf_static parent=<p> child=<c> x= y= z= qx= qy= qz= qw= age_ns=
///   map_odom stamp_ns= x= y= z= angle_deg= age_ns=
///   tf_check stamp_ns= matched=1 pos_err_m= rot_err_deg= odom_step_m= odom_step_deg=
///            odom_step_dt_ns= pose_age_ns= tf_age_ns= map_odom_stamp_ns=
///   tf_check stamp_ns= matched=0 reason=<no_odom_base_link|no_map_odom|no_tf_static|frame>
///            pose_age_ns=
///
/// age_ns = receiver's CLOCK_REALTIME when the sample was taken − its stamp. A pose waits for
/// its transforms (the pose and /tf are separate topics; either may arrive first) until /tf
/// has moved 1 s past its stamp, then is reported unmatched.

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tf_buffer.h"

namespace swlio::tools::fastdds_echo {

struct TfCheckFrames {
  std::string map = "map";
  std::string odom = "odom";
  std::string base = "base_link";
};

class TfCheck {
 public:
  using Emit = std::function<void(const std::string& line)>;
  TfCheck(TfCheckFrames frames, Emit emit) : frames_(std::move(frames)), emit_(std::move(emit)) {}

  /// One transform of a /tf sample, taken at `now_ns` (CLOCK_REALTIME). Other frames than the
  /// map → odom → base_link chain are ignored.
  void OnTransform(int64_t stamp_ns,
                   const std::string& parent,
                   const std::string& child,
                   const Eigen::Isometry3d& T_parent_child,
                   int64_t now_ns);
  /// After the transforms of one /tf sample: resolves the poses that waited for them.
  void OnTfDone() { Resolve(false); }
  /// A /tf_static sample.
  void OnStatic(const std::vector<StaticTransform>& transforms,
                const std::vector<int64_t>& stamps_ns,
                int64_t now_ns);
  /// A pose (`frame` is its header's frame_id) taken at `now_ns`.
  void OnPose(int64_t stamp_ns,
              const std::string& frame,
              const Eigen::Isometry3d& T_map_base,
              int64_t now_ns);
  /// At exit: the poses still waiting are reported unmatched.
  void Finish() { Resolve(true); }

 private:
  struct PendingPose {
    int64_t stamp_ns = 0;
    Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
    int64_t age_ns = 0;
  };
  void Resolve(bool finishing);
  /// Emits the pose's line if its transforms are there (or `give_up`); false: keep waiting.
  bool Check(const PendingPose& pose, bool give_up);
  void Unmatched(const PendingPose& pose, const char* reason);

  TfCheckFrames frames_;
  Emit emit_;
  TfBuffer buffer_;
  std::deque<PendingPose> pending_;
};

}  // namespace swlio::tools::fastdds_echo

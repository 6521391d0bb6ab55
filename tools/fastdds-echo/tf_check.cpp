#include "tf_check.h"

#include <cinttypes>
#include <cstdio>

namespace swlio::tools::fastdds_echo {
namespace {

constexpr int64_t kGiveUpNs = 1'000'000'000;  // /tf this far past a pose: its transform is lost

/// One line of at most 511 characters (the longest, a pose's, is about 330).
template <typename... Args>
std::string Format(const char* format, Args... args) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, format, args...);
  return buffer;
}

}  // namespace

void TfCheck::OnTransform(int64_t stamp_ns,
                          const std::string& parent,
                          const std::string& child,
                          const Eigen::Isometry3d& T_parent_child,
                          int64_t now_ns) {
  const int64_t age_ns = now_ns - stamp_ns;
  if (parent == frames_.odom && child == frames_.base) {
    buffer_.AddOdomBase(stamp_ns, T_parent_child, age_ns);
  } else if (parent == frames_.map && child == frames_.odom) {
    buffer_.AddMapOdom(stamp_ns, T_parent_child);
    const Eigen::Vector3d& t = T_parent_child.translation();
    emit_(Format("map_odom stamp_ns=%" PRId64
                 " x=%.17g y=%.17g z=%.17g angle_deg=%.17g age_ns=%" PRId64,
                 stamp_ns, t.x(), t.y(), t.z(),
                 AngleDeg(Eigen::Isometry3d::Identity(), T_parent_child), age_ns));
  }
}

void TfCheck::OnStatic(const std::vector<StaticTransform>& transforms,
                       const std::vector<int64_t>& stamps_ns,
                       int64_t now_ns) {
  for (size_t i = 0; i < transforms.size(); ++i) {
    const StaticTransform& s = transforms[i];
    const Eigen::Vector3d& t = s.T_parent_child.translation();
    const Eigen::Quaterniond q(s.T_parent_child.linear());
    emit_(
        Format("tf_static parent=%s child=%s x=%.17g y=%.17g z=%.17g qx=%.17g qy=%.17g "
               "qz=%.17g qw=%.17g age_ns=%" PRId64,
               s.parent.c_str(), s.child.c_str(), t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w(),
               now_ns - stamps_ns[i]));
  }
  buffer_.SetStatic(transforms);
  Resolve(false);
}

void TfCheck::OnPose(int64_t stamp_ns,
                     const std::string& frame,
                     const Eigen::Isometry3d& T_map_base,
                     int64_t now_ns) {
  const PendingPose pose{stamp_ns, T_map_base, now_ns - stamp_ns};
  if (frame != frames_.map) {
    Unmatched(pose, "frame");
    return;
  }
  pending_.push_back(pose);
  Resolve(false);
}

void TfCheck::Resolve(bool finishing) {
  while (!pending_.empty()) {
    const PendingPose& pose = pending_.front();
    const bool give_up = finishing || buffer_.newest_odom_stamp_ns() - pose.stamp_ns > kGiveUpNs;
    if (!Check(pose, give_up)) return;  // in stamp order: the later ones wait too
    pending_.pop_front();
  }
}

bool TfCheck::Check(const PendingPose& pose, bool give_up) {
  // A tf2 lookup from map to base_link succeeds once the tree is connected; the sensors hang
  // off base_link by /tf_static (rviz2 needs them to place the robot's sensors).
  bool statics = false;
  for (const StaticTransform& s : buffer_.statics()) statics = statics || s.parent == frames_.base;
  const OdomSample* odom = buffer_.OdomBaseAt(pose.stamp_ns);
  if (odom == nullptr || !statics) {
    if (give_up) Unmatched(pose, odom == nullptr ? "no_odom_base_link" : "no_tf_static");
    return give_up;
  }
  const auto map_odom = buffer_.MapOdomAt(pose.stamp_ns);
  if (!map_odom) {
    Unmatched(pose, "no_map_odom");
    return true;
  }
  const Eigen::Isometry3d T_map_base = map_odom->second * odom->T_odom_base;
  const double pos_err_m = (T_map_base.translation() - pose.T_map_base.translation()).norm();
  emit_(Format("tf_check stamp_ns=%" PRId64 " matched=1 pos_err_m=%.17g rot_err_deg=%.17g "
               "odom_step_m=%.17g odom_step_deg=%.17g odom_step_dt_ns=%" PRId64
               " pose_age_ns=%" PRId64 " tf_age_ns=%" PRId64 " map_odom_stamp_ns=%" PRId64,
               pose.stamp_ns, pos_err_m, AngleDeg(T_map_base, pose.T_map_base), odom->step_m,
               odom->step_deg, odom->has_step ? odom->step_dt_ns : 0, pose.age_ns, odom->age_ns,
               map_odom->first));
  return true;
}

void TfCheck::Unmatched(const PendingPose& pose, const char* reason) {
  emit_(Format("tf_check stamp_ns=%" PRId64 " matched=0 reason=%s pose_age_ns=%" PRId64,
               pose.stamp_ns, reason, pose.age_ns));
}

}  // namespace swlio::tools::fastdds_echo

#include "tf_buffer.h"

#include <cmath>
#include <iterator>

namespace swlio::tools::fastdds_echo {

double AngleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::AngleAxisd d(a.linear().transpose() * b.linear());
  return d.angle() * 180.0 / M_PI;
}

void TfBuffer::AddMapOdom(int64_t stamp_ns, const Eigen::Isometry3d& T_map_odom) {
  map_odom_[stamp_ns] = T_map_odom;
  while (map_odom_.size() > capacity_) map_odom_.erase(map_odom_.begin());
}

void TfBuffer::AddOdomBase(int64_t stamp_ns, const Eigen::Isometry3d& T_odom_base, int64_t age_ns) {
  OdomSample s;
  s.T_odom_base = T_odom_base;
  s.age_ns = age_ns;
  const auto next = odom_base_.lower_bound(stamp_ns);
  if (next != odom_base_.begin()) {
    const auto& [previous_ns, previous] = *std::prev(next);
    s.has_step = true;
    s.step_m = (T_odom_base.translation() - previous.T_odom_base.translation()).norm();
    s.step_deg = AngleDeg(previous.T_odom_base, T_odom_base);
    s.step_dt_ns = stamp_ns - previous_ns;
  }
  odom_base_[stamp_ns] = s;
  while (odom_base_.size() > capacity_) odom_base_.erase(odom_base_.begin());
}

std::optional<std::pair<int64_t, Eigen::Isometry3d>> TfBuffer::MapOdomAt(int64_t stamp_ns) const {
  auto it = map_odom_.upper_bound(stamp_ns);  // the first one after the stamp
  if (it == map_odom_.begin()) return std::nullopt;
  --it;
  return std::make_pair(it->first, it->second);
}

const OdomSample* TfBuffer::OdomBaseAt(int64_t stamp_ns) const {
  const auto it = odom_base_.find(stamp_ns);
  return it == odom_base_.end() ? nullptr : &it->second;
}

}  // namespace swlio::tools::fastdds_echo

#include "swlio/estimator/deskew.h"

#include <algorithm>

namespace swlio::estimator {

void PoseTrack::Add(int64_t t_ns, const Eigen::Isometry3d& T_world_imu) {
  samples_.push_back(
      {t_ns, Eigen::Quaterniond(T_world_imu.linear()).normalized(), T_world_imu.translation()});
}

bool PoseTrack::At(int64_t t_ns, Eigen::Isometry3d* T_world_imu) const {
  if (samples_.empty() || t_ns < samples_.front().t_ns || t_ns > samples_.back().t_ns) {
    return false;
  }
  auto hi = std::lower_bound(samples_.begin(), samples_.end(), t_ns,
                             [](const Sample& s, int64_t t) { return s.t_ns < t; });
  if (hi == samples_.begin()) hi = std::next(hi);
  if (hi == samples_.end()) hi = std::prev(hi);
  const Sample& b = *hi;
  const Sample& a = *std::prev(hi);
  const double span = static_cast<double>(b.t_ns - a.t_ns);
  const double u = span > 0.0 ? static_cast<double>(t_ns - a.t_ns) / span : 0.0;
  T_world_imu->setIdentity();
  T_world_imu->linear() = a.q.slerp(u, b.q).toRotationMatrix();
  T_world_imu->translation() = (1.0 - u) * a.p + u * b.p;
  return true;
}

DeskewResult Deskew(const Scan& scan,
                    const PoseTrack& track,
                    const Eigen::Isometry3d& T_imu_lidar,
                    std::vector<Eigen::Vector3d>* out) {
  DeskewResult result;
  out->resize(scan.points.size());
  Eigen::Isometry3d T_world_imu_end;
  if (!track.At(scan.t_end_ns, &T_world_imu_end)) {
    for (size_t i = 0; i < scan.points.size(); ++i) {
      (*out)[i] = scan.points[i].xyz_m.cast<double>();
    }
    result.uncovered = scan.points.size();
    return result;
  }
  const Eigen::Isometry3d T_end_world = (T_world_imu_end * T_imu_lidar).inverse();
  Eigen::Isometry3d T_world_imu;
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const LidarPoint& pt = scan.points[i];
    const Eigen::Vector3d p = pt.xyz_m.cast<double>();
    if (track.At(scan.t_start_ns + pt.dt_ns, &T_world_imu)) {
      (*out)[i] = T_end_world * (T_world_imu * (T_imu_lidar * p));
    } else {
      (*out)[i] = p;
      ++result.uncovered;
    }
  }
  result.points = scan.points.size();
  return result;
}

}  // namespace swlio::estimator

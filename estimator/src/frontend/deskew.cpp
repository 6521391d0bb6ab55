#include "swlio/estimator/frontend/deskew.h"

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace swlio::estimator {

void PoseTrack::Add(int64_t t_ns, const Eigen::Isometry3d& T_world_imu) {
  samples_.push_back(
      {t_ns, Eigen::Quaterniond(T_world_imu.linear()).normalized(), T_world_imu.translation()});
}

std::pair<const PoseTrack::Sample*, const PoseTrack::Sample*> PoseTrack::Around(
    int64_t t_ns) const {
  if (samples_.size() == 1) return {&samples_[0], &samples_[0]};  // t is that sample's time
  auto hi = std::lower_bound(samples_.begin(), samples_.end(), t_ns,
                             [](const Sample& s, int64_t t) { return s.t_ns < t; });
  if (hi == samples_.begin()) hi = std::next(hi);
  if (hi == samples_.end()) hi = std::prev(hi);
  return {&*std::prev(hi), &*hi};
}

bool PoseTrack::At(int64_t t_ns, int64_t max_gap_ns, Eigen::Isometry3d* T_world_imu) const {
  if (samples_.empty() || t_ns < samples_.front().t_ns || t_ns > samples_.back().t_ns) {
    return false;
  }
  const auto [pa, pb] = Around(t_ns);
  const Sample& a = *pa;
  const Sample& b = *pb;
  const bool between = a.t_ns < t_ns && t_ns < b.t_ns;
  if (between && b.t_ns - a.t_ns > max_gap_ns) return false;
  const double span = static_cast<double>(b.t_ns - a.t_ns);
  const double u = span > 0.0 ? static_cast<double>(t_ns - a.t_ns) / span : 0.0;
  T_world_imu->setIdentity();
  T_world_imu->linear() = a.q.slerp(u, b.q).toRotationMatrix();
  T_world_imu->translation() = (1.0 - u) * a.p + u * b.p;
  return true;
}

bool PoseTrack::At(int64_t t_ns, Eigen::Isometry3d* T_world_imu) const {
  return At(t_ns, std::numeric_limits<int64_t>::max(), T_world_imu);
}

void PoseTrack::DropBefore(int64_t t_ns) {
  const auto first = std::lower_bound(samples_.begin(), samples_.end(), t_ns,
                                      [](const Sample& s, int64_t t) { return s.t_ns < t; });
  samples_.erase(samples_.begin(), first);
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
  // Points fired within kReuseNs of each other share one transform (a firing sequence of 16
  // lasers spans 55.5 µs): at 1.5 m/s and 60 °/s that moves a point 30 m away by < 0.7 mm.
  constexpr int64_t kReuseNs = 20'000;
  Eigen::Isometry3d T_world_imu;
  Eigen::Isometry3d T_end_point = Eigen::Isometry3d::Identity();
  int64_t t_cached = std::numeric_limits<int64_t>::min();
  bool cached_ok = false;
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const LidarPoint& pt = scan.points[i];
    const int64_t t_ns = scan.t_start_ns + pt.dt_ns;
    if (t_cached == std::numeric_limits<int64_t>::min() || std::abs(t_ns - t_cached) > kReuseNs) {
      cached_ok = track.At(t_ns, &T_world_imu);
      if (cached_ok) T_end_point = T_end_world * T_world_imu * T_imu_lidar;
      t_cached = t_ns;
    }
    const Eigen::Vector3d p = pt.xyz_m.cast<double>();
    if (cached_ok && t_ns >= track.begin_ns() && t_ns <= track.end_ns()) {
      (*out)[i] = T_end_point * p;
    } else {
      (*out)[i] = p;
      ++result.uncovered;
    }
  }
  result.points = scan.points.size();
  return result;
}

}  // namespace swlio::estimator

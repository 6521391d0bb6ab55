#include "swlio/estimator/frontend/deskew.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace swlio::estimator {

void PoseTrack::Add(int64_t t_ns, const Eigen::Isometry3d& T_world_imu) {
  samples_.push_back(
      {t_ns, Eigen::Quaterniond(T_world_imu.linear()).normalized(), T_world_imu.translation()});
  if (samples_.size() < 2) return;
  Sample& a = samples_[samples_.size() - 2];
  a.dot_next = a.q.dot(samples_.back().q);
  a.theta_next = std::acos(std::abs(a.dot_next));
  a.sin_theta_next = std::sin(a.theta_next);
}

// Eigen's QuaternionBase::slerp (Eigen 3.4, Geometry/Quaternion.h) term for term, with its dot
// product, acos and first sin taken from `a`: the same operations on the same values.
Eigen::Quaterniond PoseTrack::Slerp(const Sample& a, const Sample& b, double u) {
  const double one = 1.0 - std::numeric_limits<double>::epsilon();
  const double abs_dot = std::abs(a.dot_next);
  double scale0 = 1.0 - u;
  double scale1 = u;
  if (abs_dot < one) {
    scale0 = std::sin((1.0 - u) * a.theta_next) / a.sin_theta_next;
    scale1 = std::sin(u * a.theta_next) / a.sin_theta_next;
  }
  if (a.dot_next < 0.0) scale1 = -scale1;
  return Eigen::Quaterniond(scale0 * a.q.coeffs() + scale1 * b.q.coeffs());
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
  // A single sample (a is b) has no kept terms.
  const Eigen::Quaterniond q = pa == pb ? a.q.slerp(u, b.q) : Slerp(a, b, u);
  T_world_imu->linear() = q.toRotationMatrix();
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

namespace {

/// The de-skew of every point of `scan`: `write(i, p)` receives point i in the LiDAR frame at
/// `scan.t_end_ns` (as measured when the track does not cover its time).
template <typename Write>
DeskewResult DeskewEach(const Scan& scan,
                        const PoseTrack& track,
                        const Eigen::Isometry3d& T_imu_lidar,
                        Write write) {
  DeskewResult result;
  Eigen::Isometry3d T_world_imu_end;
  if (!track.At(scan.t_end_ns, &T_world_imu_end)) {
    for (size_t i = 0; i < scan.points.size(); ++i) write(i, scan.points[i].xyz_m.cast<double>());
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
      write(i, T_end_point * p);
    } else {
      write(i, p);
      ++result.uncovered;
    }
  }
  result.points = scan.points.size();
  return result;
}

}  // namespace

DeskewResult Deskew(const Scan& scan,
                    const PoseTrack& track,
                    const Eigen::Isometry3d& T_imu_lidar,
                    std::vector<Eigen::Vector3d>* out) {
  out->resize(scan.points.size());
  return DeskewEach(scan, track, T_imu_lidar,
                    [out](size_t i, const Eigen::Vector3d& p_lidar) { (*out)[i] = p_lidar; });
}

DeskewResult DeskewScan(const Scan& scan,
                        const PoseTrack& track,
                        const Eigen::Isometry3d& T_imu_lidar,
                        Scan* out) {
  out->t_start_ns = scan.t_start_ns;
  out->t_end_ns = scan.t_end_ns;
  out->seq = scan.seq;
  out->partial = scan.partial;
  out->points.resize(scan.points.size());  // capacity kept from the last sweep: no allocation
  LidarPoint* points = out->points.data();
  const LidarPoint* in = scan.points.data();
  return DeskewEach(scan, track, T_imu_lidar,
                    [points, in](size_t i, const Eigen::Vector3d& p_lidar) {
                      points[i] = in[i];
                      points[i].xyz_m = p_lidar.cast<float>();
                    });
}

}  // namespace swlio::estimator

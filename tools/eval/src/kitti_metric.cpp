// KITTI odometry metric (devkit evaluate_odometry.cpp conventions, see kitti_metric.h).

#include "swlio/eval/kitti_metric.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swlio::eval {
namespace {

std::vector<double> TrajectoryDistances(const Trajectory& gt) {
  std::vector<double> dist_m(gt.Size(), 0.0);
  for (std::size_t i = 1; i < gt.Size(); ++i) {
    dist_m[i] = dist_m[i - 1] + (gt.Position(i) - gt.Position(i - 1)).norm();
  }
  return dist_m;
}

/// First frame l ≥ first with dist[l] > dist[first] + length, or npos.
std::size_t LastFrameOfSegment(const std::vector<double>& dist_m,
                               std::size_t first,
                               double length_m) {
  for (std::size_t i = first; i < dist_m.size(); ++i) {
    if (dist_m[i] > dist_m[first] + length_m) return i;
  }
  return static_cast<std::size_t>(-1);
}

double DevkitRotationError(const Pose& E) {
  const double d = 0.5 * (E(0, 0) + E(1, 1) + E(2, 2) - 1.0);
  return std::acos(std::clamp(d, -1.0, 1.0));
}

}  // namespace

KittiResult KittiOdometryMetric(const Trajectory& gt,
                                const Trajectory& est,
                                const KittiOptions& options) {
  if (gt.Size() != est.Size()) {
    throw EvalError("KITTI metric needs equal pose counts (" + std::to_string(gt.Size()) + " vs " +
                    std::to_string(est.Size()) + ")");
  }
  if (options.step_frames == 0) throw EvalError("KITTI metric step must be >= 1 frame");
  const std::vector<double> dist_m = TrajectoryDistances(gt);
  KittiResult out;
  for (std::size_t first = 0; first < gt.Size(); first += options.step_frames) {
    for (double length_m : options.lengths_m) {
      const std::size_t last = LastFrameOfSegment(dist_m, first, length_m);
      if (last == static_cast<std::size_t>(-1)) continue;
      const Pose delta_gt = gt.poses[first].inverse() * gt.poses[last];
      const Pose delta_est = est.poses[first].inverse() * est.poses[last];
      const Pose E = delta_est.inverse() * delta_gt;
      out.segments.push_back({first, last, length_m, E.block<3, 1>(0, 3).norm() / length_m,
                              DevkitRotationError(E) / length_m});
    }
  }
  if (out.segments.empty()) {
    throw EvalError("KITTI metric: the ground truth path (" + std::to_string(dist_m.back()) +
                    " m) is shorter than every segment length");
  }
  constexpr double kRadToDeg100 = 180.0 / std::numbers::pi * 100.0;
  for (double length_m : options.lengths_m) {
    KittiLengthSummary s;
    s.length_m = length_m;
    for (const KittiSegment& seg : out.segments) {
      if (seg.length_m != length_m) continue;
      ++s.n;
      s.t_err_percent += seg.t_err_ratio;
      s.r_err_deg_per_100m += seg.r_err_rad_per_m;
    }
    if (s.n == 0) continue;
    s.t_err_percent *= 100.0 / static_cast<double>(s.n);
    s.r_err_deg_per_100m *= kRadToDeg100 / static_cast<double>(s.n);
    out.per_length.push_back(s);
  }
  for (const KittiSegment& seg : out.segments) {
    out.t_err_percent += seg.t_err_ratio;
    out.r_err_deg_per_100m += seg.r_err_rad_per_m;
  }
  const double n = static_cast<double>(out.segments.size());
  out.t_err_percent *= 100.0 / n;
  out.r_err_deg_per_100m *= kRadToDeg100 / n;
  return out;
}

}  // namespace swlio::eval

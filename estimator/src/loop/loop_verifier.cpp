#include "swlio/estimator/loop/loop_verifier.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <tuple>
#include <utility>

namespace swlio::estimator {
namespace {

/// Share and count of planar features within `distance_m` of the plane their neighbours form.
std::pair<double, size_t> PlaneFitness(const ScanMatcher& matcher,
                                       const std::vector<Eigen::Vector3d>& planes_lidar,
                                       const LoopSubmap& submap,
                                       const Eigen::Isometry3d& T,
                                       double distance_m) {
  if (planes_lidar.empty()) return {0.0, 0};
  std::vector<PlaneCorrespondence> planes;
  std::vector<LineCorrespondence> lines;
  matcher.Associate(planes_lidar, {}, submap.planes, submap.edges, T, &planes, &lines);
  size_t inliers = 0;
  for (const PlaneCorrespondence& c : planes) {
    const Eigen::Vector3d x = T * planes_lidar[c.index];
    if (std::abs(c.normal.dot(x - c.centroid)) < distance_m) ++inliers;
  }
  return {static_cast<double>(inliers) / static_cast<double>(planes_lidar.size()), inliers};
}

}  // namespace

const char* ToString(LoopVerdict verdict) {
  switch (verdict) {
    case LoopVerdict::kAccepted:
      return "accepted";
    case LoopVerdict::kNotConverged:
      return "registration did not converge";
    case LoopVerdict::kLowFitness:
      return "too few features on the submap's surfaces";
    case LoopVerdict::kDegenerate:
      return "registration not constrained in every direction";
    case LoopVerdict::kImplausibleCorrection:
      return "correction larger than the drift can be";
  }
  return "?";
}

LoopCheck VerifyLoop(const LoopClosureConfig& config,
                     const std::vector<Eigen::Vector3d>& planes_lidar,
                     const std::vector<Eigen::Vector3d>& edges_lidar,
                     const LoopSubmap& submap,
                     const Eigen::Isometry3d& T_candidate_lidar_guess) {
  LoopCheck out;
  const ScanMatcher coarse(config.coarse);
  const ScanMatcher fine(config.fine);
  const MatchResult c =
      coarse.Match(planes_lidar, edges_lidar, submap.planes, submap.edges, T_candidate_lidar_guess);
  const MatchResult f =
      fine.Match(planes_lidar, edges_lidar, submap.planes, submap.edges, c.T_world_lidar);
  out.T_candidate_lidar = f.T_world_lidar;
  out.min_eigenvalue = f.hessian_eigenvalues(0);
  const Eigen::Isometry3d delta = T_candidate_lidar_guess.inverse() * f.T_world_lidar;
  out.correction_m = delta.translation().norm();
  out.correction_rad = Eigen::AngleAxisd(delta.rotation()).angle();
  std::tie(out.fitness, out.inliers) =
      PlaneFitness(fine, planes_lidar, submap, f.T_world_lidar, config.inlier_distance_m);
  if (!f.converged) {
    out.verdict = LoopVerdict::kNotConverged;
  } else if (out.fitness < config.min_fitness ||
             out.inliers < static_cast<size_t>(config.min_inliers)) {
    out.verdict = LoopVerdict::kLowFitness;
  } else if (!(out.min_eigenvalue >= config.min_hessian_eigenvalue)) {
    out.verdict = LoopVerdict::kDegenerate;
  } else if (out.correction_m > config.max_correction_m ||
             out.correction_rad > config.max_correction_rad) {
    out.verdict = LoopVerdict::kImplausibleCorrection;
  } else {
    out.verdict = LoopVerdict::kAccepted;
  }
  return out;
}

}  // namespace swlio::estimator

#include "swlio/estimator/scan_matcher.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

using Mat36 = Eigen::Matrix<double, 3, 6>;

/// Centroid and covariance eigen-decomposition (ascending eigenvalues) of neighbours.
struct Fit {
  Eigen::Vector3d centroid;
  Eigen::Vector3d eigenvalues;
  Eigen::Matrix3d eigenvectors;
};

Fit FitPoints(const std::vector<Eigen::Vector3d>& pts) {
  Fit f;
  f.centroid = Eigen::Vector3d::Zero();
  for (const auto& p : pts) f.centroid += p;
  f.centroid /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - f.centroid) * (p - f.centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov / static_cast<double>(pts.size()));
  f.eigenvalues = es.eigenvalues();
  f.eigenvectors = es.eigenvectors();
  return f;
}

/// ∂(T·Exp(ξ)·p)/∂ξ at ξ = 0, ξ = [ρ; φ].
Mat36 PointJacobian(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Mat36 J;
  J.leftCols<3>() = R;
  J.rightCols<3>() = -R * lie::Hat(p);
  return J;
}

/// The `config.neighbors` nearest map points of `x` and their fit; false when there are fewer.
bool FitNeighbours(const VoxelMap& map,
                   const Eigen::Vector3d& x,
                   const ScanMatcherConfig& config,
                   std::vector<Eigen::Vector3d>* nn,
                   Fit* fit) {
  if (map.Nearest(x, config.neighbors, config.max_neighbor_distance_m, nn) < config.neighbors) {
    return false;
  }
  *fit = FitPoints(*nn);
  return true;
}

}  // namespace

ConfigIssues ScanMatcherConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange<size_t>(issues, "neighbors", neighbors, 3, 20);
  CheckInRange(issues, "max_neighbor_distance_m", max_neighbor_distance_m, 0.1, 10.0);
  CheckInRange(issues, "plane_max_distance_m", plane_max_distance_m, 0.001, 1.0);
  CheckInRange(issues, "plane_min_spread_ratio", plane_min_spread_ratio, 0.0, 1.0);
  CheckInRange(issues, "line_min_ratio", line_min_ratio, 1.0, 100.0);
  CheckPositive(issues, "huber_m", huber_m);
  CheckPositive(issues, "max_residual_m", max_residual_m);
  CheckInRange(issues, "max_iterations", max_iterations, 1, 100);
  return issues;
}

ScanMatcher::ScanMatcher(const ScanMatcherConfig& config) : config_(config) {}

double ScanMatcher::HuberWeight(double r) const {
  const double a = std::abs(r);
  return a <= config_.huber_m ? 1.0 : config_.huber_m / a;
}

void ScanMatcher::AddPlanes(const std::vector<Eigen::Vector3d>& pts,
                            const VoxelMap& map,
                            const Eigen::Isometry3d& T,
                            Normal* ne) const {
  std::vector<Eigen::Vector3d> nn;
  Fit f;
  for (const Eigen::Vector3d& p : pts) {
    const Eigen::Vector3d x = T * p;
    if (!FitNeighbours(map, x, config_, &nn, &f)) continue;
    // Neighbours along one scan line (a ring on the ground, a row on a wall) are collinear:
    // their "plane" normal is arbitrary and would tie the sweep to the previous sensor position.
    if (f.eigenvalues(1) < config_.plane_min_spread_ratio * f.eigenvalues(2)) continue;
    const Eigen::Vector3d n = f.eigenvectors.col(0);
    bool planar = true;
    for (const auto& q : nn)
      planar = planar && std::abs(n.dot(q - f.centroid)) <= config_.plane_max_distance_m;
    const double r = n.dot(x - f.centroid);
    if (!planar || std::abs(r) > config_.max_residual_m) continue;
    const Eigen::Matrix<double, 1, 6> J = n.transpose() * PointJacobian(T.linear(), p);
    const double w = HuberWeight(r);
    ne->H += w * J.transpose() * J;
    ne->b += w * J.transpose() * r;
    ne->cost += w * r * r;
    ++ne->planes;
  }
}

void ScanMatcher::AddEdges(const std::vector<Eigen::Vector3d>& pts,
                           const VoxelMap& map,
                           const Eigen::Isometry3d& T,
                           Normal* ne) const {
  std::vector<Eigen::Vector3d> nn;
  Fit f;
  for (const Eigen::Vector3d& p : pts) {
    const Eigen::Vector3d x = T * p;
    if (!FitNeighbours(map, x, config_, &nn, &f)) continue;
    if (f.eigenvalues(2) < config_.line_min_ratio * f.eigenvalues(1)) continue;
    const Eigen::Vector3d d = f.eigenvectors.col(2);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
    const Eigen::Vector3d e = P * (x - f.centroid);
    const double r = e.norm();
    if (r > config_.max_residual_m) continue;
    const Mat36 J = P * PointJacobian(T.linear(), p);
    const double w = HuberWeight(r);
    ne->H += w * J.transpose() * J;
    ne->b += w * J.transpose() * e;
    ne->cost += w * r * r;
    ++ne->edges;
  }
}

MatchResult ScanMatcher::Match(const std::vector<Eigen::Vector3d>& planar_lidar,
                               const std::vector<Eigen::Vector3d>& edge_lidar,
                               const VoxelMap& plane_map,
                               const VoxelMap& edge_map,
                               const Eigen::Isometry3d& T_init) const {
  MatchResult result;
  Eigen::Isometry3d T = T_init;
  Normal ne;
  for (int it = 0; it < config_.max_iterations; ++it) {
    ne = Normal{};
    AddPlanes(planar_lidar, plane_map, T, &ne);
    AddEdges(edge_lidar, edge_map, T, &ne);
    result.iterations = it + 1;
    if (ne.planes + ne.edges < 6) break;  // too few constraints to solve
    const Eigen::Matrix<double, 6, 1> delta = ne.H.ldlt().solve(-ne.b);
    if (!delta.allFinite()) break;
    T = T * lie::ExpSE3(delta);
    if (delta.head<3>().norm() < config_.converged_translation_m &&
        delta.tail<3>().norm() < config_.converged_rotation_rad) {
      result.converged = true;
      break;
    }
  }
  result.T_world_lidar = T;
  result.plane_inliers = ne.planes;
  result.edge_inliers = ne.edges;
  result.cost = ne.cost;
  result.hessian = ne.H;
  result.hessian_eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(ne.H, Eigen::EigenvaluesOnly)
          .eigenvalues();
  return result;
}

}  // namespace swlio::estimator

#include "swlio/estimator/registration/scan_matcher.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

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
  // Closed form for 3×3 (Eigen's computeDirect): the iterative QR had cost ~1,000 instructions
  // per fit, and a registration fits ~1,100 features per association.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov / static_cast<double>(pts.size()));
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

}  // namespace

ConfigIssues ScanMatcherConfig::Validate() const {
  ConfigIssues issues;
  constexpr size_t kMostNeighbours = 20;
  // Surface searches one more (neighbour_cache.h).
  static_assert(kMostNeighbours + 1 <= VoxelMap::kMaxNeighbours);
  CheckInRange<size_t>(issues, "neighbors", neighbors, 3, kMostNeighbours);
  CheckInRange(issues, "max_neighbor_distance_m", max_neighbor_distance_m, 0.1, 10.0);
  CheckInRange(issues, "plane_max_distance_m", plane_max_distance_m, 0.001, 1.0);
  CheckInRange(issues, "plane_min_spread_ratio", plane_min_spread_ratio, 0.0, 1.0);
  CheckInRange(issues, "line_min_ratio", line_min_ratio, 1.0, 100.0);
  CheckPositive(issues, "huber_m", huber_m);
  CheckPositive(issues, "max_residual_m", max_residual_m);
  CheckInRange(issues, "refined_max_residual_m", refined_max_residual_m, 0.01, max_residual_m);
  CheckInRange(issues, "max_iterations", max_iterations, 1, 100);
  CheckInRange(issues, "max_associations", max_associations, 1, 100);
  CheckInRange(issues, "reassociate_translation_m", reassociate_translation_m, 0.0, 1.0);
  CheckInRange(issues, "reassociate_rotation_rad", reassociate_rotation_rad, 0.0, 0.5);
  return issues;
}

ScanMatcher::ScanMatcher(const ScanMatcherConfig& config) : config_(config) {}

double ScanMatcher::HuberWeight(double r) const {
  const double a = std::abs(r);
  return a <= config_.huber_m ? 1.0 : config_.huber_m / a;
}

void ScanMatcher::Associate(const std::vector<Eigen::Vector3d>& planar_lidar,
                            const std::vector<Eigen::Vector3d>& edge_lidar,
                            const VoxelMap& plane_map,
                            const VoxelMap& edge_map,
                            const Eigen::Isometry3d& T,
                            std::vector<PlaneCorrespondence>* planes,
                            std::vector<LineCorrespondence>* lines,
                            NeighbourCache* cache) const {
  NeighbourCache local;
  Associate(planar_lidar, edge_lidar, plane_map, edge_map, T, config_.refined_max_residual_m,
            cache != nullptr ? *cache : local, planes, lines);
}

const CachedSurface& ScanMatcher::Surface(const VoxelMap& map,
                                          const Eigen::Vector3d& x,
                                          bool plane,
                                          std::vector<Eigen::Vector3d>* nn,
                                          CachedSurface* entry) const {
  const Eigen::Vector3d moved = x - entry->query_world;
  if (entry->margin_m >= 0.0 && moved.squaredNorm() < entry->margin_m * entry->margin_m &&
      map.SameVoxel(x, entry->query_world)) {
    return *entry;
  }
  *entry = CachedSurface{};
  entry->query_world = x;
  // One neighbour more than needed: its distance bounds how far the query may move before it
  // could take the place of the k-th (neighbour_cache.h).
  const size_t k = config_.neighbors;
  const size_t found = map.Nearest(x, k + 1, config_.max_neighbor_distance_m, nn);
  if (found < k) return *entry;  // no entry: searched again next time
  const double kth_m = ((*nn)[k - 1] - x).norm();
  const double next_m = found > k ? ((*nn)[k] - x).norm() : config_.max_neighbor_distance_m;
  entry->margin_m = 0.5 * (next_m - kth_m) - 1e-9;  // less a rounding allowance
  nn->resize(k);
  // The fit of the set, whatever the order they were found in: a query moved within the
  // margin may find them in another order, and must still get the same fit to the last bit.
  std::sort(nn->begin(), nn->end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  const Fit f = FitPoints(*nn);
  entry->centroid = f.centroid;
  if (plane) {
    // Neighbours along one scan line (a ring on the ground, a row on a wall) are collinear:
    // their "plane" normal is arbitrary and would tie the sweep to the previous sensor position.
    entry->axis = f.eigenvectors.col(0);
    entry->valid =
        f.eigenvalues(1) >= config_.plane_min_spread_ratio * f.eigenvalues(2) &&
        std::all_of(nn->begin(), nn->end(), [&](const Eigen::Vector3d& q) {
          return std::abs(entry->axis.dot(q - f.centroid)) <= config_.plane_max_distance_m;
        });
  } else {
    entry->axis = f.eigenvectors.col(2);
    entry->valid = f.eigenvalues(2) >= config_.line_min_ratio * f.eigenvalues(1);
  }
  return *entry;
}

void ScanMatcher::Associate(const std::vector<Eigen::Vector3d>& planar_lidar,
                            const std::vector<Eigen::Vector3d>& edge_lidar,
                            const VoxelMap& plane_map,
                            const VoxelMap& edge_map,
                            const Eigen::Isometry3d& T,
                            double max_residual_m,
                            NeighbourCache& cache,
                            std::vector<PlaneCorrespondence>* planes,
                            std::vector<LineCorrespondence>* lines) const {
  planes->clear();
  lines->clear();
  std::vector<Eigen::Vector3d> nn;
  nn.reserve(config_.neighbors + 1);
  std::vector<CachedSurface>& plane_entries = cache.planes.For(plane_map, planar_lidar.size());
  for (size_t i = 0; i < planar_lidar.size(); ++i) {
    const Eigen::Vector3d x = T * planar_lidar[i];
    const CachedSurface& s = Surface(plane_map, x, true, &nn, &plane_entries[i]);
    if (!s.valid || std::abs(s.axis.dot(x - s.centroid)) > max_residual_m) continue;
    planes->push_back({static_cast<uint32_t>(i), s.axis, s.centroid});
  }
  std::vector<CachedSurface>& edge_entries = cache.edges.For(edge_map, edge_lidar.size());
  for (size_t i = 0; i < edge_lidar.size(); ++i) {
    const Eigen::Vector3d x = T * edge_lidar[i];
    const CachedSurface& s = Surface(edge_map, x, false, &nn, &edge_entries[i]);
    if (!s.valid) continue;
    const Eigen::Vector3d e = (x - s.centroid) - s.axis * s.axis.dot(x - s.centroid);
    if (e.norm() > max_residual_m) continue;
    lines->push_back({static_cast<uint32_t>(i), s.axis, s.centroid});
  }
}

void ScanMatcher::Accumulate(const std::vector<Eigen::Vector3d>& planar_lidar,
                             const std::vector<Eigen::Vector3d>& edge_lidar,
                             const std::vector<PlaneCorrespondence>& planes,
                             const std::vector<LineCorrespondence>& lines,
                             const Eigen::Isometry3d& T,
                             Normal* ne) const {
  for (const PlaneCorrespondence& c : planes) {
    const Eigen::Vector3d& p = planar_lidar[c.index];
    const double r = c.normal.dot(T * p - c.centroid);
    const Eigen::Matrix<double, 1, 6> J = c.normal.transpose() * PointJacobian(T.linear(), p);
    const double w = HuberWeight(r);
    ne->H.noalias() += w * J.transpose() * J;
    ne->b.noalias() += w * J.transpose() * r;
    ne->cost += w * r * r;
    ++ne->planes;
  }
  for (const LineCorrespondence& c : lines) {
    const Eigen::Vector3d& p = edge_lidar[c.index];
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - c.direction * c.direction.transpose();
    const Eigen::Vector3d e = P * (T * p - c.centroid);
    const double r = e.norm();
    const Mat36 J = P * PointJacobian(T.linear(), p);
    const double w = HuberWeight(r);
    ne->H.noalias() += w * J.transpose() * J;
    ne->b.noalias() += w * J.transpose() * e;
    ne->cost += w * r * r;
    ++ne->edges;
  }
}

MatchResult ScanMatcher::Match(const std::vector<Eigen::Vector3d>& planar_lidar,
                               const std::vector<Eigen::Vector3d>& edge_lidar,
                               const VoxelMap& plane_map,
                               const VoxelMap& edge_map,
                               const Eigen::Isometry3d& T_init,
                               NeighbourCache* cache) const {
  NeighbourCache local;
  NeighbourCache& searches = cache != nullptr ? *cache : local;
  MatchResult result;
  Eigen::Isometry3d T = T_init;
  Eigen::Isometry3d T_associated = T_init;
  std::vector<PlaneCorrespondence> planes;
  std::vector<LineCorrespondence> lines;
  Associate(planar_lidar, edge_lidar, plane_map, edge_map, T, config_.max_residual_m, searches,
            &planes, &lines);
  bool fresh = true;
  int associations = 1;
  Normal ne;
  for (int it = 0; it < config_.max_iterations; ++it) {
    ne = Normal{};
    Accumulate(planar_lidar, edge_lidar, planes, lines, T, &ne);
    result.iterations = it + 1;
    if (ne.planes + ne.edges < 6) break;  // too few constraints to solve
    const Eigen::Matrix<double, 6, 1> delta = ne.H.ldlt().solve(-ne.b);
    if (!delta.allFinite()) break;
    T = T * lie::ExpSE3(delta);
    const bool final_set = associations >= config_.max_associations;
    if ((fresh || final_set) && delta.head<3>().norm() < config_.converged_translation_m &&
        delta.tail<3>().norm() < config_.converged_rotation_rad) {
      result.converged = true;
      break;
    }
    const Eigen::Isometry3d moved = T_associated.inverse() * T;
    fresh = !final_set &&
            (moved.translation().norm() > config_.reassociate_translation_m ||
             Eigen::AngleAxisd(moved.linear()).angle() > config_.reassociate_rotation_rad ||
             delta.head<3>().norm() < config_.converged_translation_m);
    if (fresh) {
      Associate(planar_lidar, edge_lidar, plane_map, edge_map, T, config_.refined_max_residual_m,
                searches, &planes, &lines);
      T_associated = T;
      ++associations;
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

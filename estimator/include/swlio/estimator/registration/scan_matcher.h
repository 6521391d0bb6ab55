#pragma once
/// @file
/// Scan-to-map registration: point-to-plane residuals for planar features and point-to-line
/// residuals for edge features against a VoxelMap, solved by Gauss–Newton on SE(3) with a
/// Huber kernel. Correspondences are found at the start and again whenever the pose has moved
/// more than `reassociate_*` since they were found; in between, Gauss–Newton re-linearizes
/// the same planes and lines (LOAM does the same every few iterations), which saves most
/// neighbour searches once the pose settles. Convergence is only declared on fresh ones.
///
/// Residuals (T = T_world_lidar, p a feature point in the LiDAR frame, x = T p):
///   plane: r = nᵀ (x − c)             c, n: centroid and normal of the k nearest map points
///   line:  r = (I − d dᵀ)(x − c)      c, d: centroid and direction of the k nearest map points
/// Perturbation on the right, T ← T · Exp([ρ; φ]) (lie.h): ∂x/∂ρ = R, ∂x/∂φ = −R Hat(p), so
///   plane J = nᵀ R [I, −Hat(p)],  line J = (I − d dᵀ) R [I, −Hat(p)].
/// A correspondence is kept only when the neighbours really form a plane (all within
/// `plane_max_distance_m` of it) or a line (largest eigenvalue ≥ `line_min_ratio` × the next).
/// The eigenvalues of the final 6×6 Gauss–Newton Hessian measure how well each direction is
/// constrained (degeneracy, Zhang et al., ICRA 2016).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "swlio/core/config_issue.h"
#include "swlio/estimator/registration/neighbour_cache.h"
#include "swlio/estimator/registration/voxel_map.h"

namespace swlio::estimator {

struct ScanMatcherConfig {
  size_t neighbors = 5;  ///< map points per correspondence
  double max_neighbor_distance_m = 1.5;
  double plane_max_distance_m = 0.1;  ///< neighbour-to-plane bound for a valid plane
  /// A plane needs neighbours spread in two directions: λ_mid ≥ this × λ_max of their
  /// covariance (collinear neighbours, e.g. one ring on the ground, define no plane).
  double plane_min_spread_ratio = 0.05;
  /// A line needs its neighbours spread along it: λ1 ≥ this × λ2 of their covariance. LOAM's 3
  /// takes five edge points scattered over a flat face for a line about half the time (points
  /// whose smoothness passed the edge threshold by noise, or beside a silhouette); that "line"
  /// lies in the face and pulls the sweep along it. On the simulated gantry posts a third of the
  /// edge features were such points, and the map's corner lines sat 4–5 cm inside the faces. A
  /// corner's or a pole's neighbours give λ1/λ2 in the hundreds. One run each, no loop closure
  /// (docs/notes/2026-12-06-edge-lines-on-faces.md): the 42 `aggressive` drives of seeds 1–3 and
  /// 42, with each disturbance, 0.952 m summed at 3, 0.773 m at 6, 0.711 m at 10 (every one
  /// lower than at 3); `loop943` and `field` 1–3 0.179 / 0.158 / 0.159 m. The dynamic
  /// bootstrap's young map keeps its own, looser test (DynamicBootstrapConfig::line_min_ratio).
  double line_min_ratio = 10.0;
  double huber_m = 0.1;  ///< Huber kernel width
  /// Larger residuals are outliers in the first association, made at a predicted pose.
  double max_residual_m = 1.0;
  /// The same once the pose is registered: later associations of a match, and `Associate`.
  /// A feature this far from its map surface (4σ of the window's 0.05 m) has found the wrong
  /// one. Typically a surface coming into view found the one seen before just behind it, such
  /// as the far face of a wall. Against a map built from the true poses, the simulated 0.3 m
  /// firewalls pulled the yaw by 0.2° as the far face came into view
  /// (docs/notes/2026-11-24-residual-gate.md).
  double refined_max_residual_m = 0.2;
  int max_iterations = 10;
  /// Correspondence searches per match at most (each costs ~1.7 ms on a 1,100-feature sweep);
  /// after the last, Gauss–Newton finishes on that set.
  int max_associations = 4;
  double reassociate_translation_m = 0.02;  ///< pose change that triggers new neighbours
  double reassociate_rotation_rad = 0.004;
  double converged_translation_m = 1e-3;  ///< a step below both ends the solve
  double converged_rotation_rad = 1e-4;

  ConfigIssues Validate() const;
};

struct MatchResult {
  Eigen::Isometry3d T_world_lidar = Eigen::Isometry3d::Identity();
  bool converged = false;
  int iterations = 0;
  size_t plane_inliers = 0;
  size_t edge_inliers = 0;
  double cost = 0.0;  ///< robust cost at the final pose
  Eigen::Matrix<double, 6, 6> hessian = Eigen::Matrix<double, 6, 6>::Zero();  ///< [ρ; φ] order
  Eigen::Matrix<double, 6, 1> hessian_eigenvalues =
      Eigen::Matrix<double, 6, 1>::Zero();  ///< ascending
  /// Directions left to the IMU because the scan does not constrain them (the window
  /// estimator's degeneracy test; 0 from ScanMatcher itself).
  int degenerate_directions = 0;
};

/// A feature point (index into its input vector) paired with a plane or a line of the map.
struct PlaneCorrespondence {
  uint32_t index = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};
struct LineCorrespondence {
  uint32_t index = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< unit
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

class ScanMatcher {
 public:
  explicit ScanMatcher(const ScanMatcherConfig& config = {});

  /// Registers LiDAR-frame features against the maps (either may be empty) from `T_init`.
  /// `cache` (optional, for these features): searches kept from an earlier call and for a
  /// later one; the result is the same with or without it (neighbour_cache.h).
  MatchResult Match(const std::vector<Eigen::Vector3d>& planar_lidar,
                    const std::vector<Eigen::Vector3d>& edge_lidar,
                    const VoxelMap& plane_map,
                    const VoxelMap& edge_map,
                    const Eigen::Isometry3d& T_init,
                    NeighbourCache* cache = nullptr) const;

  /// Pairs every feature, placed at `T_world_lidar` (a registered pose: the gate is
  /// `refined_max_residual_m`), with the plane or line its map neighbours form (validity checks
  /// as above); features without one are left out. `cache` as for Match.
  void Associate(const std::vector<Eigen::Vector3d>& planar_lidar,
                 const std::vector<Eigen::Vector3d>& edge_lidar,
                 const VoxelMap& plane_map,
                 const VoxelMap& edge_map,
                 const Eigen::Isometry3d& T_world_lidar,
                 std::vector<PlaneCorrespondence>* planes,
                 std::vector<LineCorrespondence>* lines,
                 NeighbourCache* cache = nullptr) const;

 private:
  void Associate(const std::vector<Eigen::Vector3d>& planar_lidar,
                 const std::vector<Eigen::Vector3d>& edge_lidar,
                 const VoxelMap& plane_map,
                 const VoxelMap& edge_map,
                 const Eigen::Isometry3d& T_world_lidar,
                 double max_residual_m,
                 NeighbourCache& cache,
                 std::vector<PlaneCorrespondence>* planes,
                 std::vector<LineCorrespondence>* lines) const;
  /// The surface the neighbours of `x` form, from `entry` when it still holds, else searched
  /// and fitted into it.
  const CachedSurface& Surface(const VoxelMap& map,
                               const Eigen::Vector3d& x,
                               bool plane,
                               std::vector<Eigen::Vector3d>* nn,
                               CachedSurface* entry) const;
  struct Normal {  ///< accumulated Gauss–Newton system
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
    double cost = 0.0;
    size_t planes = 0;
    size_t edges = 0;
  };
  void Accumulate(const std::vector<Eigen::Vector3d>& planar_lidar,
                  const std::vector<Eigen::Vector3d>& edge_lidar,
                  const std::vector<PlaneCorrespondence>& planes,
                  const std::vector<LineCorrespondence>& lines,
                  const Eigen::Isometry3d& T,
                  Normal* ne) const;
  double HuberWeight(double r) const;

  ScanMatcherConfig config_;
};

}  // namespace swlio::estimator

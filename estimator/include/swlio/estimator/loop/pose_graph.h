#pragma once
/// @file
/// Pose graph of keyframe IMU poses (issue 8): odometry edges between consecutive keyframes
/// and loop edges from verified loop closures, each a RelativePoseFactor
/// (relative_pose_factor.h). The first node is held fixed (the gauge).
/// Consistency: after a solve, the loop edge with the largest whitened squared residual (χ², 6
/// degrees of freedom) above `max_loop_chi2` is switched off and the graph solved again, until
/// every active loop agrees with the odometry and the other loops: a wrong loop that passed
/// verification cannot be satisfied without bending the odometry, a right one can. A robust
/// kernel on loop edges (optional) is no substitute: it also ignores a right loop after a long
/// drift, whose residual before the solve is large.
/// GNSS (optional, gnss_factor.h): position factors on nodes through one more block, the
/// map-to-ENU alignment (yaw and translation), which must be set (its initial value) before the
/// first GNSS edge. They take a Huber kernel, and after the loop check every GNSS edge whose
/// whitened squared residual (3 DoF) exceeds `max_gnss_chi2` is switched off (a multipath
/// jump with an optimistic accuracy), then the graph is solved again.
/// Solved by Ceres (sparse normal Cholesky: the graph is a long chain with a few shortcuts).
/// Pure library: the caller decides when to optimize (the daemon in its own thread).

#include <ceres/loss_function.h>

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <deque>
#include <memory>
#include <vector>

#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/gnss/gnss_factor.h"
#include "swlio/estimator/loop/relative_pose_factor.h"

namespace swlio::estimator {

struct PoseGraphSummary {
  bool solved = false;
  int iterations = 0;  ///< summed over the solves
  int solves = 0;
  double initial_cost = 0.0;      ///< of the first solve
  double final_cost = 0.0;        ///< of the last
  size_t loops_switched_off = 0;  ///< by this call's consistency check
  size_t gnss_switched_off = 0;   ///< by this call's GNSS check
};

class PoseGraph {
 public:
  /// `loop_kernel`: Cauchy scale on the whitened loop residual (≤ 0: no kernel);
  /// `max_loop_chi2`: the consistency bound (≤ 0: no check).
  explicit PoseGraph(double loop_kernel = 0.0, double max_loop_chi2 = 0.0);
  PoseGraph(const PoseGraph&) = delete;
  PoseGraph& operator=(const PoseGraph&) = delete;

  /// Adds a node at its initial pose; returns its index (0, 1, …).
  size_t AddNode(const Eigen::Isometry3d& T_world_imu);
  /// T_i_j measured (j's pose in i's frame). False when an index is out of range, i == j, or
  /// the measurement is not finite.
  bool AddOdometryEdge(size_t i, size_t j, const Eigen::Isometry3d& T_i_j, const Mat6& sqrt_info);
  bool AddLoopEdge(size_t i, size_t j, const Eigen::Isometry3d& T_i_j, const Mat6& sqrt_info);

  /// GNSS edges: Huber scale on the whitened residual (≤ 0: none) and the χ² bound (≤ 0: no
  /// check).
  void SetGnssRobustness(double kernel, double max_chi2);
  /// Starts (or resets) the map-to-ENU alignment at T_enu_map's yaw and translation.
  void SetEnuAlignment(const Eigen::Isometry3d& T_enu_map);
  bool has_enu_alignment() const { return has_alignment_; }
  Eigen::Isometry3d T_enu_map() const { return EnuFromAlignment(alignment_.data()); }
  /// A fix of the antenna (at `antenna_imu_m` in node i's IMU frame) at `fix_enu_m`. False
  /// without an alignment, with i out of range or a bad value.
  bool AddGnssEdge(size_t i,
                   const Eigen::Vector3d& antenna_imu_m,
                   const Eigen::Vector3d& fix_enu_m,
                   double sigma_h_m,
                   double sigma_v_m);
  size_t gnss_edges() const { return gnss_.size(); }
  size_t gnss_switched_off() const { return gnss_switched_off_; }

  PoseGraphSummary Optimize(int max_iterations = 20);

  size_t size() const { return nodes_.size(); }
  /// Moves every node by `A` (T ← A · T): the whole graph in another world frame; odometry and
  /// loop edges are relative and unchanged (GNSS edges are not: do not call with them).
  void TransformAll(const Eigen::Isometry3d& A);
  size_t loop_edges() const { return loop_edges_; }
  /// Loop edges switched off by the consistency check so far.
  size_t loops_switched_off() const { return switched_off_; }
  /// Whitened squared residual of loop edge k (in the order added) at the current poses, and
  /// whether it is still active.
  double LoopChi2(size_t k) const;
  bool LoopActive(size_t k) const;
  Eigen::Isometry3d pose(size_t i) const { return PoseFromParameters(nodes_[i].data()); }

 private:
  struct Edge {
    size_t i = 0, j = 0;
    bool loop = false;
    bool active = true;
    std::unique_ptr<RelativePoseFactor> factor;
  };
  bool AddEdge(size_t i, size_t j, const Eigen::Isometry3d& T_i_j, const Mat6& S, bool loop);
  double Chi2(const Edge& e) const;
  /// One Ceres solve over the active edges.
  bool Solve(int max_iterations, PoseGraphSummary* summary);
  const Edge* LoopEdge(size_t k) const;
  /// Switches off the GNSS edges above the χ² bound; how many.
  size_t SwitchOffGnssOutliers();
  struct GnssEdge {
    size_t i = 0;
    bool active = true;
    std::unique_ptr<GnssPositionFactor> factor;
  };

  std::deque<std::array<double, kPoseSize>> nodes_;  ///< deque: blocks keep their addresses
  std::vector<Edge> edges_;
  PoseManifold manifold_;
  std::unique_ptr<ceres::LossFunction> loop_loss_;  ///< null: no kernel
  double max_loop_chi2_;
  size_t loop_edges_ = 0;
  size_t switched_off_ = 0;
  std::vector<GnssEdge> gnss_;
  EnuAlignment alignment_{};
  std::unique_ptr<ceres::LossFunction> gnss_loss_;  ///< null: no kernel
  double max_gnss_chi2_ = 0.0;
  size_t gnss_switched_off_ = 0;
  bool has_alignment_ = false;
};

}  // namespace swlio::estimator

#include "swlio/estimator/loop/pose_graph.h"

#include <ceres/problem.h>
#include <ceres/solver.h>

#include <cmath>

namespace swlio::estimator {

PoseGraph::PoseGraph(double loop_kernel, double max_loop_chi2)
    : loop_loss_(loop_kernel > 0.0 ? std::make_unique<ceres::CauchyLoss>(loop_kernel) : nullptr),
      max_loop_chi2_(max_loop_chi2) {}

size_t PoseGraph::AddNode(const Eigen::Isometry3d& T_world_imu) {
  nodes_.emplace_back();
  PoseToParameters(T_world_imu, nodes_.back().data());
  return nodes_.size() - 1;
}

void PoseGraph::TransformAll(const Eigen::Isometry3d& A) {
  for (auto& node : nodes_) PoseToParameters(A * PoseFromParameters(node.data()), node.data());
}

bool PoseGraph::AddOdometryEdge(size_t i,
                                size_t j,
                                const Eigen::Isometry3d& T_i_j,
                                const Mat6& sqrt_info) {
  return AddEdge(i, j, T_i_j, sqrt_info, false);
}

bool PoseGraph::AddLoopEdge(size_t i,
                            size_t j,
                            const Eigen::Isometry3d& T_i_j,
                            const Mat6& sqrt_info) {
  if (!AddEdge(i, j, T_i_j, sqrt_info, true)) return false;
  ++loop_edges_;
  return true;
}

bool PoseGraph::AddEdge(
    size_t i, size_t j, const Eigen::Isometry3d& T_i_j, const Mat6& S, bool loop) {
  if (i >= nodes_.size() || j >= nodes_.size() || i == j) return false;
  auto factor = RelativePoseFactor::Create(T_i_j, S);
  if (factor == nullptr) return false;
  edges_.push_back(Edge{i, j, loop, true, std::move(factor)});
  return true;
}

void PoseGraph::SetGnssRobustness(double kernel, double max_chi2) {
  gnss_loss_ = kernel > 0.0 ? std::make_unique<ceres::HuberLoss>(kernel) : nullptr;
  max_gnss_chi2_ = max_chi2;
}

void PoseGraph::SetEnuAlignment(const Eigen::Isometry3d& T_enu_map) {
  const Eigen::Vector3d x = T_enu_map.linear().col(0);
  alignment_ = {std::atan2(x.y(), x.x()), T_enu_map.translation().x(), T_enu_map.translation().y(),
                T_enu_map.translation().z()};
  has_alignment_ = true;
}

bool PoseGraph::AddGnssEdge(size_t i,
                            const Eigen::Vector3d& antenna_imu_m,
                            const Eigen::Vector3d& fix_enu_m,
                            double sigma_h_m,
                            double sigma_v_m) {
  if (!has_alignment_ || i >= nodes_.size()) return false;
  auto factor = GnssPositionFactor::Create(antenna_imu_m, fix_enu_m, sigma_h_m, sigma_v_m);
  if (factor == nullptr) return false;
  gnss_.push_back(GnssEdge{i, true, std::move(factor)});
  return true;
}

size_t PoseGraph::SwitchOffGnssOutliers() {
  size_t n = 0;
  if (max_gnss_chi2_ <= 0.0) return n;
  for (GnssEdge& g : gnss_) {
    if (g.active && g.factor->Chi2(nodes_[g.i].data(), alignment_.data()) > max_gnss_chi2_) {
      g.active = false;
      ++n;
    }
  }
  gnss_switched_off_ += n;
  return n;
}

bool PoseGraph::Solve(int max_iterations, PoseGraphSummary* out) {
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (auto& node : nodes_) problem.AddParameterBlock(node.data(), kPoseSize, &manifold_);
  problem.SetParameterBlockConstant(nodes_.front().data());
  for (Edge& e : edges_) {
    if (!e.active) continue;
    problem.AddResidualBlock(e.factor.get(), e.loop ? loop_loss_.get() : nullptr,
                             nodes_[e.i].data(), nodes_[e.j].data());
  }
  if (has_alignment_ && !gnss_.empty()) {
    problem.AddParameterBlock(alignment_.data(), kEnuAlignmentSize);
    for (GnssEdge& g : gnss_) {
      if (g.active) {
        problem.AddResidualBlock(g.factor.get(), gnss_loss_.get(), nodes_[g.i].data(),
                                 alignment_.data());
      }
    }
  }
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  so.max_num_iterations = max_iterations;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  if (out->solves++ == 0) out->initial_cost = summary.initial_cost;
  out->final_cost = summary.final_cost;
  out->iterations += static_cast<int>(summary.iterations.size());
  return summary.IsSolutionUsable();
}

double PoseGraph::Chi2(const Edge& e) const {
  const double* blocks[2] = {nodes_[e.i].data(), nodes_[e.j].data()};
  Eigen::Matrix<double, 6, 1> r;
  if (!e.factor->Evaluate(blocks, r.data(), nullptr)) return 0.0;
  return r.squaredNorm();
}

PoseGraphSummary PoseGraph::Optimize(int max_iterations) {
  PoseGraphSummary out;
  if (nodes_.size() < 2 || (edges_.empty() && gnss_.empty())) return out;
  out.solved = Solve(max_iterations, &out);
  while (out.solved && max_loop_chi2_ > 0.0) {
    Edge* worst = nullptr;
    double worst_chi2 = max_loop_chi2_;
    for (Edge& e : edges_) {
      if (!e.loop || !e.active) continue;
      if (const double chi2 = Chi2(e); chi2 > worst_chi2) {
        worst_chi2 = chi2;
        worst = &e;
      }
    }
    if (worst == nullptr) break;
    worst->active = false;  // it disagrees with everything else: switch it off and solve again
    ++out.loops_switched_off;
    ++switched_off_;
    out.solved = Solve(max_iterations, &out);
  }
  // GNSS outliers: a few rounds (a jump pulls its neighbours until it is gone).
  for (int round = 0; round < 3 && out.solved; ++round) {
    const size_t n = SwitchOffGnssOutliers();
    if (n == 0) break;
    out.gnss_switched_off += n;
    out.solved = Solve(max_iterations, &out);
  }
  return out;
}

const PoseGraph::Edge* PoseGraph::LoopEdge(size_t k) const {
  for (const Edge& e : edges_) {
    if (e.loop && k-- == 0) return &e;
  }
  return nullptr;
}

double PoseGraph::LoopChi2(size_t k) const {
  const Edge* e = LoopEdge(k);
  return e != nullptr ? Chi2(*e) : 0.0;
}

bool PoseGraph::LoopActive(size_t k) const {
  const Edge* e = LoopEdge(k);
  return e != nullptr && e->active;
}

}  // namespace swlio::estimator

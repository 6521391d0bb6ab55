#include "swlio/estimator/pose_graph.h"

#include <ceres/problem.h>
#include <ceres/solver.h>

namespace swlio::estimator {

PoseGraph::PoseGraph(double loop_kernel, double max_loop_chi2)
    : loop_loss_(loop_kernel > 0.0 ? std::make_unique<ceres::CauchyLoss>(loop_kernel) : nullptr),
      max_loop_chi2_(max_loop_chi2) {}

size_t PoseGraph::AddNode(const Eigen::Isometry3d& T_world_imu) {
  nodes_.emplace_back();
  PoseToParameters(T_world_imu, nodes_.back().data());
  return nodes_.size() - 1;
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
  if (nodes_.size() < 2 || edges_.empty()) return out;
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

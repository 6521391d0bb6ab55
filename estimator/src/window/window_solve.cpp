// WindowEstimator's optimization: the window problem, its solve, the newest state's covariance,
// re-integration at new biases and the marginalization of the oldest frame.

#include <ceres/crs_matrix.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <Eigen/Cholesky>
#include <algorithm>

#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"
#include "swlio/estimator/window/window_estimator.h"
#include "window_frame.h"

namespace swlio::estimator {

ceres::Problem::Options WindowEstimator::ProblemOptions() {
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.enable_fast_removal = false;
  return po;
}

void WindowEstimator::BuildProblem(ceres::Problem& problem) {
  problem.AddParameterBlock(extrinsic_.data(), kPoseSize, &manifold_);
  if (config_.estimate_extrinsic) {
    problem.AddResidualBlock(extrinsic_prior_.get(), nullptr, extrinsic_.data());
  } else {
    problem.SetParameterBlockConstant(extrinsic_.data());
  }
  if (config_.estimate_gravity_tilt)
    problem.AddParameterBlock(gravity_tilt_.data(), kGravityTiltSize);
  if (FollowsOffset()) {
    problem.AddParameterBlock(window_offset_s_.data(), 1);
    problem.SetParameterBlockConstant(window_offset_s_.data());
  }
  if (offset_free_) {
    problem.AddParameterBlock(window_offset_s_.data(), 1);
    problem.SetParameterLowerBound(window_offset_s_.data(), 0, -config_.time_offset.max_offset_s);
    problem.SetParameterUpperBound(window_offset_s_.data(), 0, config_.time_offset.max_offset_s);
    if (offset_prior_ != nullptr) {
      problem.AddResidualBlock(offset_prior_.get(), nullptr, window_offset_s_.data());
    }
  }
  for (size_t k = 0; k < frames_.size(); ++k) {
    Frame& f = *frames_[k];
    problem.AddParameterBlock(f.pose.data(), kPoseSize, &manifold_);
    problem.AddParameterBlock(f.speed_bias.data(), kSpeedBiasSize);
    if (bias_prior_ != nullptr) {
      problem.AddResidualBlock(bias_prior_.get(), nullptr, f.speed_bias.data());
    }
    if (f.lidar_linear != nullptr) {
      problem.AddResidualBlock(f.lidar_linear.get(), nullptr, LidarBlocks(&f));
    }
    if (k > 0 && f.imu != nullptr) {
      auto [cost, blocks] = ImuTerm(*frames_[k - 1], f);
      problem.AddResidualBlock(cost, nullptr, blocks);
    }
    if (f.wheel != nullptr) {
      problem.AddResidualBlock(f.wheel.get(), nullptr, f.pose.data(), f.speed_bias.data());
    }
    if (f.zero_velocity != nullptr) {
      problem.AddResidualBlock(f.zero_velocity.get(), nullptr, f.speed_bias.data());
    }
  }
  if (prior_.prior != nullptr) {
    problem.AddResidualBlock(prior_.prior.get(), nullptr, prior_.kept_blocks);
  }
}

WindowEstimator::FrameImuOptions WindowEstimator::ImuFactorOptions() const {
  return {noise_adapter_.Effective(), config_.odometry.estimator.gravity_mps2,
          config_.estimate_gravity_tilt, offset_free_ || FollowsOffset()};
}

std::pair<ceres::CostFunction*, std::vector<double*>> WindowEstimator::ImuTerm(Frame& p, Frame& f) {
  std::vector<double*> blocks = {p.pose.data(), p.speed_bias.data(), f.pose.data(),
                                 f.speed_bias.data()};
  if (config_.estimate_gravity_tilt) blocks.push_back(gravity_tilt_.data());
  if (f.imu_offset != nullptr) blocks.push_back(window_offset_s_.data());
  return {f.ImuCost(config_.estimate_gravity_tilt), std::move(blocks)};
}

int WindowEstimator::Solve(WindowResult* result) {
  result->lidar_factors = 0;
  for (const auto& f : frames_) result->lidar_factors += f->plane_factors + f->line_factors;
  ceres::Problem problem(ProblemOptions());
  BuildProblem(problem);
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  so.max_num_iterations = config_.max_iterations;
  so.initial_trust_region_radius = 1e12;  // nearly Gauss–Newton: the problem is close to linear
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);

  return static_cast<int>(summary.iterations.size());
}

namespace {

/// H = JᵀJ of a sparse Jacobian, row by row: a row adds the outer product of its non-zeros.
/// Ceres' rows are short (an IMU row touches two frames, a prior row its blocks), so this costs
/// Σ nnz(row)² instead of the dense product's rows·cols² (2.6 M instructions per sweep, 6 % of
/// the update, with an 87-column window; docs/notes/2026-12-02-per-sweep-time-250m-map.md).
Eigen::MatrixXd NormalMatrix(const ceres::CRSMatrix& J) {
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(J.num_cols, J.num_cols);
  for (size_t r = 0; r < static_cast<size_t>(J.num_rows); ++r) {
    const auto begin = static_cast<size_t>(J.rows[r]);
    const auto end = static_cast<size_t>(J.rows[r + 1]);
    for (size_t a = begin; a < end; ++a) {
      const double v = J.values[a];
      const Eigen::Index i = J.cols[a];
      for (size_t b = a; b < end; ++b) {
        const Eigen::Index j = J.cols[b];
        H(std::min(i, j), std::max(i, j)) += v * J.values[b];  // the upper triangle
      }
    }
  }
  return H.selfadjointView<Eigen::Upper>();
}

}  // namespace

StateCovariance WindowEstimator::NewestCovariance() {
  // The marginal covariance of the newest frame's blocks over the whole window problem at the
  // solution: the newest 15 columns of H⁻¹, H = JᵀJ in the tangent (no robust losses in the
  // window). Dense: H is at most 81×81. ceres::Covariance (DENSE_SVD) took 5 ms per sweep here.
  StateCovariance out;
  ceres::Problem problem(ProblemOptions());
  BuildProblem(problem);
  ceres::Problem::EvaluateOptions eo;
  if (config_.estimate_extrinsic) eo.parameter_blocks.push_back(extrinsic_.data());
  if (config_.estimate_gravity_tilt) eo.parameter_blocks.push_back(gravity_tilt_.data());
  if (offset_free_) eo.parameter_blocks.push_back(window_offset_s_.data());
  for (const auto& f : frames_) {  // the newest frame's blocks come last
    eo.parameter_blocks.push_back(f->pose.data());
    eo.parameter_blocks.push_back(f->speed_bias.data());
  }
  ceres::CRSMatrix crs;
  if (!problem.Evaluate(eo, nullptr, nullptr, nullptr, &crs)) return out;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(NormalMatrix(crs));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return out;
  // Columns of H⁻¹: the newest frame's 15, then the map tilt's (its block comes after the
  // extrinsic's, first in eo).
  const Eigen::Index n = ldlt.rows();
  const Eigen::Index n_tilt = config_.estimate_gravity_tilt ? kGravityTiltSize : 0;
  const Eigen::Index tilt_at = config_.estimate_extrinsic ? kPoseTangentSize : 0;
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(n, kStateCovSize + n_tilt);
  E.bottomLeftCorner(kStateCovSize, kStateCovSize).setIdentity();
  E.block(tilt_at, kStateCovSize, n_tilt, n_tilt).setIdentity();
  const Eigen::MatrixXd X = ldlt.solve(E);
  const StateCovarianceMatrix C = X.bottomLeftCorner(kStateCovSize, kStateCovSize);
  const Eigen::Matrix3d R = PoseFromParameters(frames_.back()->pose.data()).linear();
  out.P = ToWorldRotationAxes(C, R);
  out.rot_gravity = out.P.block<3, 3>(kCovRot, kCovRot);
  if (n_tilt > 0) {
    const Eigen::Matrix2d C_tilt = X.block(tilt_at, kStateCovSize, n_tilt, n_tilt);
    const Eigen::Matrix<double, 2, 3> C_tilt_phi = X.block(tilt_at, kCovRot, n_tilt, 3);
    out.rot_gravity =
        GravityAttitudeCovariance(C_tilt, C_tilt_phi, C.block<3, 3>(kCovRot, kCovRot),
                                  Eigen::Vector2d(gravity_tilt_[0], gravity_tilt_[1]), R);
  }
  out.valid = out.P.allFinite() && out.P.diagonal().minCoeff() > 0.0 && out.rot_gravity.allFinite();
  return out;
}

void WindowEstimator::Reintegrate() {
  for (size_t k = 1; k < frames_.size(); ++k) {
    Frame& f = *frames_[k];
    const Frame& p = *frames_[k - 1];
    if (f.pre == nullptr || !f.pre->NeedsReintegration(p.BiasGyro(), p.BiasAcc())) continue;
    f.pre->Reintegrate(p.BiasGyro(), p.BiasAcc());
    f.MakeImu(ImuFactorOptions());
  }
}

void WindowEstimator::Marginalize() {
  Frame& f0 = *frames_[0];
  Frame& f1 = *frames_[1];
  Marginalizer m;
  m.AddParameterBlock(f0.pose.data(), kPoseSize, &manifold_, BlockRole::kMarginalize);
  m.AddParameterBlock(f0.speed_bias.data(), kSpeedBiasSize, nullptr, BlockRole::kMarginalize);
  m.AddParameterBlock(f1.pose.data(), kPoseSize, &manifold_, BlockRole::kKeep);
  m.AddParameterBlock(f1.speed_bias.data(), kSpeedBiasSize, nullptr, BlockRole::kKeep);
  m.AddParameterBlock(extrinsic_.data(), kPoseSize, &manifold_,
                      config_.estimate_extrinsic ? BlockRole::kKeep : BlockRole::kConstant);
  // The frame's LiDAR rows: without them the prior would keep only IMU terms against a free
  // pose, which carry no memory of the gravity direction or the accelerometer bias.
  if (f0.lidar_linear != nullptr) {
    const std::vector<double*> blocks = LidarBlocks(&f0);
    m.AddResidualBlock(f0.lidar_linear.get(), nullptr, {blocks.begin(), blocks.end()});
  }
  if (f0.wheel != nullptr) {
    m.AddResidualBlock(f0.wheel.get(), nullptr, {f0.pose.data(), f0.speed_bias.data()});
  }
  if (f0.zero_velocity != nullptr) {
    m.AddResidualBlock(f0.zero_velocity.get(), nullptr, {f0.speed_bias.data()});
  }
  if (config_.estimate_gravity_tilt) {
    m.AddParameterBlock(gravity_tilt_.data(), kGravityTiltSize, nullptr, BlockRole::kKeep);
  }
  if (FollowsOffset()) {
    m.AddParameterBlock(window_offset_s_.data(), 1, nullptr, BlockRole::kConstant);
  }
  if (offset_free_) {
    m.AddParameterBlock(window_offset_s_.data(), 1, nullptr, BlockRole::kKeep);
    if (offset_prior_ != nullptr) {
      m.AddResidualBlock(offset_prior_.get(), nullptr, {window_offset_s_.data()});
    }
  }
  if (f1.imu != nullptr) {
    auto [cost, blocks] = ImuTerm(f0, f1);
    m.AddResidualBlock(cost, nullptr, std::move(blocks));
  }
  if (prior_.prior != nullptr) m.AddResidualBlock(prior_.prior.get(), nullptr, prior_.kept_blocks);
  MarginalizationResult next = m.Marginalize();
  if (next.status == MarginalizationStatus::kOk) {
    prior_ = std::move(next);
    offset_prior_.reset();  // folded into prior_
  } else {
    ++marginalization_failures_;
    SetRestartPrior(&f1);  // nothing carried over: restart from frame 1 as it stands
  }
  frames_.pop_front();
}

}  // namespace swlio::estimator

// Umeyama and origin alignment of trajectories; the maths is written in alignment.h.

#include "swlio/eval/alignment.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <limits>

namespace swlio::eval {

Alignment ParseAlignment(const std::string& text) {
  if (text == "none") return Alignment::kNone;
  if (text == "se3") return Alignment::kSe3;
  if (text == "sim3") return Alignment::kSim3;
  if (text == "origin") return Alignment::kOrigin;
  throw EvalError("unknown alignment '" + text + "' (expected none, se3, sim3 or origin)");
}

std::string ToString(Alignment alignment) {
  switch (alignment) {
    case Alignment::kNone:
      return "none";
    case Alignment::kSe3:
      return "se3";
    case Alignment::kSim3:
      return "sim3";
    case Alignment::kOrigin:
      return "origin";
  }
  return "?";
}

Sim3Transform Umeyama(const Eigen::Matrix3Xd& source,
                      const Eigen::Matrix3Xd& target,
                      bool with_scale) {
  if (source.cols() != target.cols()) throw EvalError("Umeyama: point sets differ in size");
  const Eigen::Index n = source.cols();
  if (n < 2) throw EvalError("Umeyama: need at least 2 point pairs");
  const double inv_n = 1.0 / static_cast<double>(n);
  const Eigen::Vector3d mean_x = source.rowwise().mean();
  const Eigen::Vector3d mean_y = target.rowwise().mean();
  const Eigen::Matrix3Xd x0 = source.colwise() - mean_x;
  const Eigen::Matrix3Xd y0 = target.colwise() - mean_y;
  const double sigma2_x = inv_n * x0.squaredNorm();
  const Eigen::Matrix3d cov_xy = inv_n * (y0 * x0.transpose());

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov_xy, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& d = svd.singularValues();
  int rank = 0;
  for (int i = 0; i < 3; ++i) rank += d(i) > std::numeric_limits<double>::epsilon() ? 1 : 0;
  if (rank < 2) throw EvalError("Umeyama: degenerate covariance (rank < 2), cannot align");

  Eigen::Vector3d s_diag(1.0, 1.0, 1.0);
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) s_diag(2) = -1.0;
  Sim3Transform out;
  out.R = svd.matrixU() * s_diag.asDiagonal() * svd.matrixV().transpose();
  out.scale = with_scale ? d.dot(s_diag) / sigma2_x : 1.0;
  out.t = mean_y - out.scale * out.R * mean_x;
  return out;
}

Pose InverseRigid(const Pose& T) {
  Pose inv = Pose::Identity();
  const Eigen::Matrix3d Rt = T.block<3, 3>(0, 0).transpose();
  inv.block<3, 3>(0, 0) = Rt;
  inv.block<3, 1>(0, 3) = -Rt * T.block<3, 1>(0, 3);
  return inv;
}

Sim3Transform Align(Trajectory& est, const Trajectory& ref, Alignment alignment) {
  if (est.Size() != ref.Size()) {
    throw EvalError("alignment needs paired trajectories (" + std::to_string(est.Size()) + " vs " +
                    std::to_string(ref.Size()) + " poses)");
  }
  if (est.Size() == 0) throw EvalError("cannot align an empty trajectory");
  Sim3Transform applied;
  if (alignment == Alignment::kNone) return applied;
  Pose T = Pose::Identity();
  if (alignment == Alignment::kOrigin) {
    T = ref.poses[0] * InverseRigid(est.poses[0]);
    applied.R = T.block<3, 3>(0, 0);
    applied.t = T.block<3, 1>(0, 3);
  } else {
    Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(est.Size()));
    Eigen::Matrix3Xd y(3, static_cast<Eigen::Index>(est.Size()));
    for (std::size_t i = 0; i < est.Size(); ++i) {
      x.col(static_cast<Eigen::Index>(i)) = est.Position(i);
      y.col(static_cast<Eigen::Index>(i)) = ref.Position(i);
    }
    applied = Umeyama(x, y, alignment == Alignment::kSim3);
    T.block<3, 3>(0, 0) = applied.R;
    T.block<3, 1>(0, 3) = applied.t;
    for (Pose& P : est.poses) P.block<3, 1>(0, 3) *= applied.scale;
  }
  for (Pose& P : est.poses) P = T * P;
  return applied;
}

}  // namespace swlio::eval

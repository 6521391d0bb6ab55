#include "swlio/estimator/loop/relative_pose_factor.h"

#include "swlio/core/lie.h"
#include "swlio/estimator/common/pose_manifold.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat67 = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;
using lie::Hat;
using lie::Log;
using lie::RightJacobianInverse;

}  // namespace

std::unique_ptr<RelativePoseFactor> RelativePoseFactor::Create(const Eigen::Isometry3d& T_i_j,
                                                               const Mat6& sqrt_information) {
  if (!sqrt_information.allFinite() || !T_i_j.matrix().allFinite()) return nullptr;
  return std::unique_ptr<RelativePoseFactor>(new RelativePoseFactor(T_i_j, sqrt_information));
}

RelativePoseFactor::RelativePoseFactor(const Eigen::Isometry3d& T_i_j, const Mat6& sqrt_information)
    : R_m_(T_i_j.rotation()), p_m_(T_i_j.translation()), sqrt_information_(sqrt_information) {}

bool RelativePoseFactor::Evaluate(double const* const* parameters,
                                  double* residuals,
                                  double** jacobians) const {
  const Eigen::Isometry3d T_i = PoseFromParameters(parameters[0]);
  const Eigen::Isometry3d T_j = PoseFromParameters(parameters[1]);
  const Mat3 R_i = T_i.rotation();
  const Mat3 R_j = T_j.rotation();
  const Vec3 d_i = R_i.transpose() * (T_j.translation() - T_i.translation());
  const Vec3 r_phi = Log(R_m_.transpose() * R_i.transpose() * R_j);
  Eigen::Matrix<double, 6, 1> r;
  r << d_i - p_m_, r_phi;
  Eigen::Map<Eigen::Matrix<double, 6, 1>>{residuals} = sqrt_information_ * r;
  if (jacobians == nullptr) return true;

  const Mat3 Jr_inv = RightJacobianInverse(r_phi);
  Mat6 J_i = Mat6::Zero();
  Mat6 J_j = Mat6::Zero();
  J_i.block<3, 3>(0, 0) = -R_i.transpose();
  J_i.block<3, 3>(0, 3) = Hat(d_i);
  J_i.block<3, 3>(3, 3) = -Jr_inv * R_j.transpose() * R_i;
  J_j.block<3, 3>(0, 0) = R_i.transpose();
  J_j.block<3, 3>(3, 3) = Jr_inv;
  const Mat6* tangent[2] = {&J_i, &J_j};
  for (int k = 0; k < 2; ++k) {
    if (jacobians[k] == nullptr) continue;
    Eigen::Map<Mat67>{jacobians[k]} =
        sqrt_information_ * *tangent[k] * PoseMinusJacobianAt(parameters[k]);
  }
  return true;
}

Mat6 DiagonalSqrtInformation(double sigma_position_m, double sigma_rotation_rad) {
  Mat6 S = Mat6::Zero();
  S.diagonal().head<3>().setConstant(1.0 / sigma_position_m);
  S.diagonal().tail<3>().setConstant(1.0 / sigma_rotation_rad);
  return S;
}

}  // namespace swlio::estimator

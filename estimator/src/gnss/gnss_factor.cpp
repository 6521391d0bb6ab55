// GNSS position factor: the maths is in gnss_factor.h.

#include "swlio/estimator/gnss/gnss_factor.h"

#include <cmath>

#include "swlio/core/lie.h"

namespace swlio::estimator {

Eigen::Isometry3d EnuFromAlignment(const double* alignment) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(alignment[0], Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(alignment[1], alignment[2], alignment[3]);
  return T;
}

std::unique_ptr<GnssPositionFactor> GnssPositionFactor::Create(const Eigen::Vector3d& antenna_imu_m,
                                                               const Eigen::Vector3d& fix_enu_m,
                                                               double sigma_h_m,
                                                               double sigma_v_m) {
  const bool ok = antenna_imu_m.allFinite() && fix_enu_m.allFinite() && std::isfinite(sigma_h_m) &&
                  std::isfinite(sigma_v_m) && sigma_h_m > 0.0 && sigma_v_m > 0.0;
  if (!ok) return nullptr;
  return std::unique_ptr<GnssPositionFactor>(
      new GnssPositionFactor(antenna_imu_m, fix_enu_m, sigma_h_m, sigma_v_m));
}

GnssPositionFactor::GnssPositionFactor(const Eigen::Vector3d& antenna_imu_m,
                                       const Eigen::Vector3d& fix_enu_m,
                                       double sigma_h_m,
                                       double sigma_v_m)
    : b_(antenna_imu_m),
      z_(fix_enu_m),
      sqrt_info_(1.0 / sigma_h_m, 1.0 / sigma_h_m, 1.0 / sigma_v_m) {}

bool GnssPositionFactor::Evaluate(double const* const* parameters,
                                  double* residuals,
                                  double** jacobians) const {
  const double* pose = parameters[0];
  const double* alignment = parameters[1];
  const Eigen::Isometry3d T = PoseFromParameters(pose);
  const Eigen::Isometry3d T_enu_map = EnuFromAlignment(alignment);
  const Eigen::Matrix3d& Rz = T_enu_map.linear();
  const Eigen::Vector3d antenna_map = T * b_;
  const Eigen::DiagonalMatrix<double, 3> S(sqrt_info_);
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = S * (T_enu_map * antenna_map - z_);
  if (jacobians == nullptr) return true;
  if (jacobians[0] != nullptr) {
    Eigen::Matrix<double, 3, kPoseTangentSize> J_delta;
    J_delta.leftCols<3>() = S * Rz;
    J_delta.rightCols<3>() = -(S * (Rz * T.linear() * lie::Hat(b_)));
    Eigen::Map<Eigen::Matrix<double, 3, kPoseSize, Eigen::RowMajor>> J(jacobians[0]);
    J = J_delta * PoseMinusJacobianAt(pose);
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, kEnuAlignmentSize, Eigen::RowMajor>> J(jacobians[1]);
    J.col(0) = S * (Rz * Eigen::Vector3d::UnitZ().cross(antenna_map));
    J.rightCols<3>() = S * Eigen::Matrix3d::Identity();
  }
  return true;
}

double GnssPositionFactor::Chi2(const double* pose, const double* alignment) const {
  const double* parameters[2] = {pose, alignment};
  Eigen::Vector3d r;
  Evaluate(parameters, r.data(), nullptr);
  return r.squaredNorm();
}

}  // namespace swlio::estimator

#include "swlio/estimator/window/state_covariance.h"

#include "swlio/core/lie.h"

namespace swlio::estimator {

StateCovarianceMatrix ToWorldRotationAxes(const StateCovarianceMatrix& C_tangent,
                                          const Eigen::Matrix3d& R_world_imu) {
  StateCovarianceMatrix J = StateCovarianceMatrix::Identity();
  J.block<3, 3>(kCovRot, kCovRot) = R_world_imu;
  StateCovarianceMatrix P = J * C_tangent * J.transpose();
  return 0.5 * (P + P.transpose());
}

Eigen::Matrix3d GravityAttitudeCovariance(const Eigen::Matrix2d& C_tilt,
                                          const Eigen::Matrix<double, 2, 3>& C_tilt_phi,
                                          const Eigen::Matrix3d& C_phi,
                                          const Eigen::Vector2d& tilt_rad,
                                          const Eigen::Matrix3d& R_map_imu) {
  const Eigen::Vector3d a(tilt_rad.x(), tilt_rad.y(), 0.0);
  Eigen::Matrix<double, 3, 5> J;
  J << lie::LeftJacobian(a).leftCols<2>(), lie::Exp(a) * R_map_imu;
  Eigen::Matrix<double, 5, 5> S;
  S << C_tilt, C_tilt_phi, C_tilt_phi.transpose(), C_phi;
  const Eigen::Matrix3d P = J * S * J.transpose();
  return 0.5 * (P + P.transpose());
}

Eigen::Matrix3d VelocityImuCovariance(const StateCovarianceMatrix& P,
                                      const Eigen::Matrix3d& R_world_imu,
                                      const Eigen::Vector3d& vel_world_mps) {
  // v_imu = Rᵀ v_w with R ← Exp(δθ) R: v_imu ≈ Rᵀ (I − [δθ]×) v_w = v_imu + Rᵀ [v_w]× δθ.
  Eigen::Matrix<double, 3, 6> J;
  J << R_world_imu.transpose() * lie::Hat(vel_world_mps), R_world_imu.transpose();
  Eigen::Matrix<double, 6, 6> S;
  S << P.block<3, 3>(kCovRot, kCovRot), P.block<3, 3>(kCovRot, kCovVel),
      P.block<3, 3>(kCovVel, kCovRot), P.block<3, 3>(kCovVel, kCovVel);
  return J * S * J.transpose();
}

}  // namespace swlio::estimator

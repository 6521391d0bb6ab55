#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"

#include <array>

#include "swlio/core/lie.h"

namespace swlio::estimator {

namespace {

using PoseJacobian = Eigen::Matrix<double, kImuFactorResiduals, 7, Eigen::RowMajor>;
using SpeedBiasJacobian =
    Eigen::Matrix<double, kImuFactorResiduals, kSpeedBiasSize, Eigen::RowMajor>;
using Residual = Eigen::Matrix<double, kImuFactorResiduals, 1>;

/// L(a) with a ⊗ b = L(a) b, quaternions in storage order (x, y, z, w).
Eigen::Matrix4d LeftProduct(const Eigen::Quaterniond& a) {
  Eigen::Matrix4d L;
  L << a.w(), -a.z(), a.y(), a.x(),  //
      a.z(), a.w(), -a.x(), a.y(),   //
      -a.y(), a.x(), a.w(), a.z(),   //
      -a.x(), -a.y(), -a.z(), a.w();
  return L;
}

void RotatePose(const Eigen::Quaterniond& Q, const double* in, double* out) {
  Eigen::Map<Eigen::Vector3d> p_out(out);
  p_out = Q * Eigen::Map<const Eigen::Vector3d>(in);
  const Eigen::Quaterniond q(in[6], in[3], in[4], in[5]);
  const Eigen::Quaterniond r = Q * q;
  out[3] = r.x();
  out[4] = r.y();
  out[5] = r.z();
  out[6] = r.w();
}

void RotateSpeedBias(const Eigen::Quaterniond& Q, const double* in, double* out) {
  Eigen::Map<Eigen::Vector3d> v_out(out + kSbVel);
  v_out = Q * Eigen::Map<const Eigen::Vector3d>(in + kSbVel);
  for (int k = kSbBiasAcc; k < kSpeedBiasSize; ++k) out[k] = in[k];
}

}  // namespace

Eigen::Quaterniond GravityTiltRotation(const double* tilt) {
  return lie::QuatExp(Eigen::Vector3d(tilt[0], tilt[1], 0.0));
}

bool GravityTiltImuFactor::EvaluateRotated(double const* const* parameters,
                                           const double* tilt,
                                           double* residuals,
                                           double** jacobians) const {
  const Eigen::Quaterniond Q = GravityTiltRotation(tilt);
  std::array<double, 7> pose_i{}, pose_j{};
  std::array<double, kSpeedBiasSize> sb_i{}, sb_j{};
  RotatePose(Q, parameters[0], pose_i.data());
  RotateSpeedBias(Q, parameters[1], sb_i.data());
  RotatePose(Q, parameters[2], pose_j.data());
  RotateSpeedBias(Q, parameters[3], sb_j.data());
  const double* rotated[4] = {pose_i.data(), sb_i.data(), pose_j.data(), sb_j.data()};
  if (jacobians == nullptr) return imu_->Evaluate(rotated, residuals, nullptr);

  PoseJacobian J_pose[2];
  SpeedBiasJacobian J_sb[2];
  double* inner[4] = {jacobians[0] != nullptr ? J_pose[0].data() : nullptr,
                      jacobians[1] != nullptr ? J_sb[0].data() : nullptr,
                      jacobians[2] != nullptr ? J_pose[1].data() : nullptr,
                      jacobians[3] != nullptr ? J_sb[1].data() : nullptr};
  if (!imu_->Evaluate(rotated, residuals, inner)) return false;
  const Eigen::Matrix3d R = Q.toRotationMatrix();
  const Eigen::Matrix4d L = LeftProduct(Q);
  for (size_t k = 0; k < 2; ++k) {
    if (jacobians[2 * k] != nullptr) {
      Eigen::Map<PoseJacobian> J(jacobians[2 * k]);
      J.leftCols<3>() = J_pose[k].leftCols<3>() * R;
      J.rightCols<4>() = J_pose[k].rightCols<4>() * L;
    }
    if (jacobians[2 * k + 1] != nullptr) {
      Eigen::Map<SpeedBiasJacobian> J(jacobians[2 * k + 1]);
      J = J_sb[k];
      J.leftCols<3>() = J_sb[k].leftCols<3>() * R;
    }
  }
  return true;
}

bool GravityTiltImuFactor::Evaluate(double const* const* parameters,
                                    double* residuals,
                                    double** jacobians) const {
  const double* tilt = parameters[4];
  if (!EvaluateRotated(parameters, tilt, residuals, jacobians)) return false;
  if (jacobians == nullptr || jacobians[4] == nullptr) return true;
  // Central difference in θ (the residual is smooth; θ stays well below a degree).
  constexpr double kStep = 1e-6;
  Eigen::Map<Eigen::Matrix<double, kImuFactorResiduals, kGravityTiltSize, Eigen::RowMajor>> J(
      jacobians[4]);
  for (int k = 0; k < kGravityTiltSize; ++k) {
    std::array<double, kGravityTiltSize> plus{tilt[0], tilt[1]}, minus{tilt[0], tilt[1]};
    plus[static_cast<size_t>(k)] += kStep;
    minus[static_cast<size_t>(k)] -= kStep;
    Residual r_plus, r_minus;
    if (!EvaluateRotated(parameters, plus.data(), r_plus.data(), nullptr) ||
        !EvaluateRotated(parameters, minus.data(), r_minus.data(), nullptr)) {
      return false;
    }
    J.col(k) = (r_plus - r_minus) / (2.0 * kStep);
  }
  return true;
}

}  // namespace swlio::estimator

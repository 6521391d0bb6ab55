#include "swlio/estimator/imu/imu_residual.h"

#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

}  // namespace

State PredictState(const State& start, const PreintegratedImu& pim, const Vec3& gravity_world) {
  const CorrectedDeltas d = Corrected(pim, start.bias_gyro, start.bias_acc);
  const Mat3 R_i = start.T_world_imu.linear();
  const Vec3 p_i = start.T_world_imu.translation();
  const double dt = pim.dt_s;
  State end = start;
  end.t_ns = start.t_ns + (pim.t_end_ns - pim.t_start_ns);
  Eigen::Quaterniond q(R_i * d.delta_R);
  q.normalize();
  end.T_world_imu.linear() = q.toRotationMatrix();
  end.T_world_imu.translation() =
      p_i + start.vel_world * dt + 0.5 * gravity_world * dt * dt + R_i * d.delta_p;
  end.vel_world = start.vel_world + gravity_world * dt + R_i * d.delta_v;
  return end;
}

// Jacobians (derivation, perturbations as in the header; cf. Forster Appendix, "Jacobians of
// the residual errors", with our additive world-frame position):
//   (R_i Exp(δ))ᵀ x ≈ R_iᵀ x + [R_iᵀ x]× δ, hence
//     ∂r_Δv/∂φ_i = [R_iᵀ(v_j − v_i − gΔt)]×,  ∂r_Δp/∂φ_i = [R_iᵀ(p_j − p_i − v_iΔt − ½gΔt²)]×.
//   Linear terms: ∂r_Δv/∂v_i = −R_iᵀ, ∂r_Δv/∂v_j = R_iᵀ, ∂r_Δp/∂p_i = −R_iᵀ, ∂r_Δp/∂p_j = R_iᵀ,
//     ∂r_Δp/∂v_i = −R_iᵀ Δt; biases: ∂r_Δv/∂b = −J_v_b, ∂r_Δp/∂b = −J_p_b.
//   Rotation, with X = ΔR(b)ᵀ R_iᵀ R_j = Exp(r):
//     R_j Exp(δ):  Log(X Exp(δ)) ≈ r + Jr⁻¹(r) δ                  → ∂r_ΔR/∂φ_j = Jr⁻¹(r)
//     R_iᵀ → Exp(−δ) R_iᵀ, and Exp(−δ) R_iᵀ R_j = R_iᵀ R_j Exp(−R_jᵀ R_i δ)
//                                                                  → ∂r_ΔR/∂φ_i = −Jr⁻¹(r) R_jᵀ R_i
//     ΔR(b + δ) ≈ ΔR(b) Exp(Jr(J_R_bg δb_g) J_R_bg δ), so X → Exp(−u) X = X Exp(−Exp(r)ᵀ u)
//                                                → ∂r_ΔR/∂b_g = −Jr⁻¹(r) Exp(r)ᵀ Jr(J_R_bg δb_g)
//                                                J_R_bg
//   (δb_g = b_g − b̄_g), and ∂r_ΔR/∂b_a = 0.
Vec9 ImuResidual(const PreintegratedImu& pim,
                 const NavPoint& si,
                 const NavPoint& sj,
                 const Vec3& bias_gyro,
                 const Vec3& bias_acc,
                 const Vec3& gravity_world,
                 ImuResidualJacobians* jacobians) {
  const CorrectedDeltas d = Corrected(pim, bias_gyro, bias_acc);
  const double dt = pim.dt_s;
  const Mat3 Rit = si.R_world_imu.transpose();
  const Vec3 dv_world = sj.v_world - si.v_world - gravity_world * dt;
  const Vec3 dp_world = sj.p_world - si.p_world - si.v_world * dt - 0.5 * gravity_world * dt * dt;
  const Vec3 v_body = Rit * dv_world;
  const Vec3 p_body = Rit * dp_world;

  Vec9 r;
  const Mat3 X = d.delta_R.transpose() * Rit * sj.R_world_imu;
  const Vec3 r_R = lie::Log(X);
  r.segment<3>(kRowR) = r_R;
  r.segment<3>(kRowV) = v_body - d.delta_v;
  r.segment<3>(kRowP) = p_body - d.delta_p;
  if (jacobians == nullptr) return r;

  ImuResidualJacobians& J = *jacobians;
  const Mat3 Jr_inv = lie::RightJacobianInverse(r_R);
  const Vec3 dbg = bias_gyro - pim.bias_gyro_lin;
  const Mat3 J_R_bg = pim.J_R_bg();
  for (Mat93* m : {&J.R_i, &J.p_i, &J.v_i, &J.R_j, &J.p_j, &J.v_j, &J.bias_gyro, &J.bias_acc}) {
    m->setZero();
  }
  J.R_i.block<3, 3>(kRowR, 0) = -Jr_inv * sj.R_world_imu.transpose() * si.R_world_imu;
  J.R_i.block<3, 3>(kRowV, 0) = lie::Hat(v_body);
  J.R_i.block<3, 3>(kRowP, 0) = lie::Hat(p_body);
  J.R_j.block<3, 3>(kRowR, 0) = Jr_inv;
  J.v_i.block<3, 3>(kRowV, 0) = -Rit;
  J.v_i.block<3, 3>(kRowP, 0) = -Rit * dt;
  J.v_j.block<3, 3>(kRowV, 0) = Rit;
  J.p_i.block<3, 3>(kRowP, 0) = -Rit;
  J.p_j.block<3, 3>(kRowP, 0) = Rit;
  J.bias_gyro.block<3, 3>(kRowR, 0) =
      -Jr_inv * X.transpose() * lie::RightJacobian(J_R_bg * dbg) * J_R_bg;
  J.bias_gyro.block<3, 3>(kRowV, 0) = -pim.J_v_bg();
  J.bias_gyro.block<3, 3>(kRowP, 0) = -pim.J_p_bg();
  J.bias_acc.block<3, 3>(kRowV, 0) = -pim.J_v_ba();
  J.bias_acc.block<3, 3>(kRowP, 0) = -pim.J_p_ba();
  return r;
}

Vec9 ImuResidual(const PreintegratedImu& pim,
                 const State& state_i,
                 const State& state_j,
                 const Vec3& gravity_world,
                 ImuResidualJacobians* jacobians) {
  return ImuResidual(pim, ToNavPoint(state_i), ToNavPoint(state_j), state_i.bias_gyro,
                     state_i.bias_acc, gravity_world, jacobians);
}

}  // namespace swlio::estimator

#include "swlio/estimator/imu/imu_factor.h"

#include <Eigen/Cholesky>

#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_residual.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec15 = Eigen::Matrix<double, kImuFactorResiduals, 1>;
using Mat15x6 = Eigen::Matrix<double, kImuFactorResiduals, kPoseTangentSize>;
using Mat15x9 = Eigen::Matrix<double, kImuFactorResiduals, kSpeedBiasSize>;

struct FrameView {
  NavPoint nav;
  Vec3 bias_acc;
  Vec3 bias_gyro;
};

FrameView ReadFrame(const double* pose, const double* speed_bias) {
  const Eigen::Isometry3d T = PoseFromParameters(pose);
  FrameView f;
  f.nav.R_world_imu = T.linear();
  f.nav.p_world = T.translation();
  f.nav.v_world = Eigen::Map<const Vec3>(speed_bias + kSbVel);
  f.bias_acc = Eigen::Map<const Vec3>(speed_bias + kSbBiasAcc);
  f.bias_gyro = Eigen::Map<const Vec3>(speed_bias + kSbBiasGyro);
  return f;
}

// Whitened tangent Jacobian of a pose block → the ambient 15×7 block Ceres expects.
void WritePose(const Mat15& W, const Mat15x6& J_delta, const double* pose, double* out) {
  Eigen::Map<Eigen::Matrix<double, kImuFactorResiduals, kPoseSize, Eigen::RowMajor>>{out} =
      W * J_delta * PoseMinusJacobianAt(pose);
}

void WriteSpeedBias(const Mat15& W, const Mat15x9& J, double* out) {
  Eigen::Map<Eigen::Matrix<double, kImuFactorResiduals, kSpeedBiasSize, Eigen::RowMajor>>{out} =
      W * J;
}

}  // namespace

std::unique_ptr<ImuFactor> ImuFactor::Create(const PreintegratedImu& pim,
                                             const ImuNoiseConfig& noise,
                                             double gravity_mps2) {
  Mat15 cov = Mat15::Zero();
  cov.topLeftCorner<9, 9>() = pim.covariance;
  cov.bottomRightCorner<6, 6>() = BiasWalkCovariance(noise, pim.dt_s);
  const Eigen::LLT<Mat15> llt(cov);
  if (pim.dt_s <= 0.0 || llt.info() != Eigen::Success) return nullptr;
  const Mat15 L = llt.matrixL();
  const Mat15 W = L.triangularView<Eigen::Lower>().solve(Mat15::Identity());
  if (!W.allFinite()) return nullptr;
  return std::unique_ptr<ImuFactor>(new ImuFactor(pim, gravity_mps2, W));
}

ImuFactor::ImuFactor(const PreintegratedImu& pim, double gravity_mps2, const Mat15& W)
    : pim_(pim), gravity_world_(GravityWorld(gravity_mps2)), sqrt_information_(W) {}

// Jacobians, with J = ImuResidualJacobians (tangent δ = [δp; δφ] for poses):
//   pose_i:        [J.p_i, J.R_i] in rows 0–8        pose_j: [J.p_j, J.R_j]
//   speed_bias_i:  [J.v_i, J.bias_acc, J.bias_gyro] in rows 0–8; −I in the bias-walk rows
//   speed_bias_j:  [J.v_j, 0, 0] in rows 0–8;                    +I in the bias-walk rows
// (frame j's biases enter only the random-walk rows: the pre-integration uses frame i's).
bool ImuFactor::Evaluate(double const* const* parameters,
                         double* residuals,
                         double** jacobians) const {
  const FrameView fi = ReadFrame(parameters[0], parameters[1]);
  const FrameView fj = ReadFrame(parameters[2], parameters[3]);
  ImuResidualJacobians J;
  const bool want_jacobians = jacobians != nullptr;
  Vec15 r;
  r.head<9>() = ImuResidual(pim_, fi.nav, fj.nav, fi.bias_gyro, fi.bias_acc, gravity_world_,
                            want_jacobians ? &J : nullptr);
  r.segment<3>(kRowBiasGyro) = fj.bias_gyro - fi.bias_gyro;
  r.segment<3>(kRowBiasAcc) = fj.bias_acc - fi.bias_acc;
  Eigen::Map<Vec15>{residuals} = sqrt_information_ * r;
  if (!want_jacobians) return true;

  const Mat15& W = sqrt_information_;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  if (jacobians[0] != nullptr) {
    Mat15x6 Jd = Mat15x6::Zero();
    Jd.topLeftCorner<9, 3>() = J.p_i;
    Jd.topRightCorner<9, 3>() = J.R_i;
    WritePose(W, Jd, parameters[0], jacobians[0]);
  }
  if (jacobians[1] != nullptr) {
    Mat15x9 Js = Mat15x9::Zero();
    Js.block<9, 3>(0, kSbVel) = J.v_i;
    Js.block<9, 3>(0, kSbBiasAcc) = J.bias_acc;
    Js.block<9, 3>(0, kSbBiasGyro) = J.bias_gyro;
    Js.block<3, 3>(kRowBiasAcc, kSbBiasAcc) = -I;
    Js.block<3, 3>(kRowBiasGyro, kSbBiasGyro) = -I;
    WriteSpeedBias(W, Js, jacobians[1]);
  }
  if (jacobians[2] != nullptr) {
    Mat15x6 Jd = Mat15x6::Zero();
    Jd.topLeftCorner<9, 3>() = J.p_j;
    Jd.topRightCorner<9, 3>() = J.R_j;
    WritePose(W, Jd, parameters[2], jacobians[2]);
  }
  if (jacobians[3] != nullptr) {
    Mat15x9 Js = Mat15x9::Zero();
    Js.block<9, 3>(0, kSbVel) = J.v_j;
    Js.block<3, 3>(kRowBiasAcc, kSbBiasAcc) = I;
    Js.block<3, 3>(kRowBiasGyro, kSbBiasGyro) = I;
    WriteSpeedBias(W, Js, jacobians[3]);
  }
  return true;
}

}  // namespace swlio::estimator

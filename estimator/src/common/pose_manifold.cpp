#include "swlio/estimator/common/pose_manifold.h"

#include "swlio/core/lie.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using ConstQuatMap = Eigen::Map<const Eigen::Quaterniond>;

}  // namespace

Eigen::Isometry3d PoseFromParameters(const double* x) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = ConstQuatMap(x + 3).normalized().toRotationMatrix();
  T.translation() = Eigen::Map<const Vec3>(x);
  return T;
}

void PoseToParameters(const Eigen::Isometry3d& T, double* x) {
  Eigen::Map<Vec3>{x} = T.translation();
  Eigen::Map<Eigen::Quaterniond>{x + 3} = Eigen::Quaterniond(T.linear()).normalized();
}

PosePlusJacobian PosePlusJacobianAt(const double* x) {
  const ConstQuatMap q(x + 3);
  PosePlusJacobian J = PosePlusJacobian::Zero();
  J.topLeftCorner<3, 3>().setIdentity();
  J.block<3, 3>(3, 3) = 0.5 * (q.w() * Eigen::Matrix3d::Identity() + lie::Hat(q.vec()));
  J.block<1, 3>(6, 3) = -0.5 * q.vec().transpose();
  return J;
}

PoseMinusJacobian PoseMinusJacobianAt(const double* x) {
  const ConstQuatMap q(x + 3);
  PoseMinusJacobian J = PoseMinusJacobian::Zero();
  J.topLeftCorner<3, 3>().setIdentity();
  J.block<3, 3>(3, 3) = 2.0 * (q.w() * Eigen::Matrix3d::Identity() - lie::Hat(q.vec()));
  J.block<3, 1>(3, 6) = -2.0 * q.vec();
  return J;
}

bool PoseManifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  Eigen::Map<Vec3>{x_plus_delta} = Eigen::Map<const Vec3>(x) + Eigen::Map<const Vec3>(delta);
  const Eigen::Quaterniond q =
      ConstQuatMap(x + 3) * lie::QuatExp(Eigen::Map<const Vec3>(delta + 3));
  Eigen::Map<Eigen::Quaterniond>{x_plus_delta + 3} = q.normalized();
  return true;
}

bool PoseManifold::PlusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<PosePlusJacobian>{jacobian} = PosePlusJacobianAt(x);
  return true;
}

bool PoseManifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  Eigen::Map<Vec3>{y_minus_x} = Eigen::Map<const Vec3>(y) - Eigen::Map<const Vec3>(x);
  const Eigen::Quaterniond dq = ConstQuatMap(x + 3).conjugate() * ConstQuatMap(y + 3);
  Eigen::Map<Vec3>{y_minus_x + 3} = lie::QuatLog(dq);
  return true;
}

bool PoseManifold::MinusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<PoseMinusJacobian>{jacobian} = PoseMinusJacobianAt(x);
  return true;
}

}  // namespace swlio::estimator

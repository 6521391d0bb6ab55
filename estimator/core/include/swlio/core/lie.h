#pragma once
/// @file
/// Small SO(3)/SE(3) toolkit (Sophus is not packaged in Debian).
///
/// Conventions:
/// - Rotation vectors `phi` (rad), |phi| = θ. `Exp(phi) = I + sinθ/θ Φ + (1−cosθ)/θ² Φ²`,
///   Φ = Hat(phi). `Log` returns the rotation vector with θ ∈ [0, π].
/// - Right Jacobian: `Exp(phi + δ) ≈ Exp(phi) Exp(Jr(phi) δ)`, and its inverse
///   `Log(Exp(phi) Exp(δ)) ≈ phi + JrInv(phi) δ` (Forster et al., "On-Manifold Preintegration",
///   TRO 2017, eq. (7)–(9)). Left Jacobians: `Jl(phi) = Jr(−phi)`.
/// - SE(3) tangent vectors are `xi = [rho; phi]` (translation part first):
///   `Exp(xi) = (Exp(phi), Jl(phi) rho)`.
/// - Quaternions are Hamilton, `Eigen::Quaterniond` (storage x, y, z, w).
///
/// Small angles use Taylor series below `kTaylorAngle`; near θ = π the half-angle forms keep
/// every formula finite.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace swlio::lie {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Below this angle (rad) series expansions replace the closed forms.
inline constexpr double kTaylorAngle = 1e-2;

/// Skew-symmetric matrix with Hat(a) b = a × b.
inline Mat3 Hat(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// Inverse of Hat for a skew-symmetric matrix (uses the antisymmetric part).
inline Vec3 Vee(const Mat3& m) {
  return 0.5 * Vec3(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

/// Unit quaternion of the rotation vector phi.
inline Eigen::Quaterniond QuatExp(const Vec3& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  double w = 0.0;
  double k = 0.0;  // sin(θ/2)/θ
  if (theta < kTaylorAngle) {
    w = 1.0 - theta2 / 8.0 + theta2 * theta2 / 384.0;
    k = 0.5 - theta2 / 48.0 + theta2 * theta2 / 3840.0;
  } else {
    w = std::cos(0.5 * theta);
    k = std::sin(0.5 * theta) / theta;
  }
  Eigen::Quaterniond q(w, k * phi.x(), k * phi.y(), k * phi.z());
  q.normalize();
  return q;
}

/// Rotation vector of a quaternion (normalized first), θ ∈ [0, π].
inline Vec3 QuatLog(const Eigen::Quaterniond& q_in) {
  Eigen::Quaterniond q = q_in.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // shortest rotation: θ ≤ π
  const Vec3 v = q.vec();
  const double n = v.norm();
  const double w = q.w();
  double scale = 0.0;  // θ / sin(θ/2)
  if (n < kTaylorAngle * 0.5 && w > 0.5) {
    // atan(n/w)·2/n = 2/w · (1 − n²/(3w²) + n⁴/(5w⁴) − …)
    const double r2 = (n * n) / (w * w);
    scale = 2.0 / w * (1.0 - r2 / 3.0 + r2 * r2 / 5.0);
  } else {
    scale = 2.0 * std::atan2(n, w) / n;
  }
  return scale * v;
}

/// Rotation matrix of the rotation vector phi.
inline Mat3 Exp(const Vec3& phi) { return QuatExp(phi).toRotationMatrix(); }

/// Rotation vector of a rotation matrix, θ ∈ [0, π]; robust at θ = 0 and θ = π.
inline Vec3 Log(const Mat3& R) { return QuatLog(Eigen::Quaterniond(R)); }

/// Angle of a rotation matrix, θ ∈ [0, π] (rad).
inline double Angle(const Mat3& R) { return Eigen::AngleAxisd(R).angle(); }

/// Right Jacobian of SO(3): Jr = I − (1−cosθ)/θ² Φ + (θ−sinθ)/θ³ Φ².
inline Mat3 RightJacobian(const Vec3& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  double a = 0.0;  // (1 − cosθ)/θ²
  double b = 0.0;  // (θ − sinθ)/θ³
  if (theta < kTaylorAngle) {
    a = 0.5 - theta2 / 24.0 + theta2 * theta2 / 720.0;
    b = 1.0 / 6.0 - theta2 / 120.0 + theta2 * theta2 / 5040.0;
  } else {
    a = (1.0 - std::cos(theta)) / theta2;
    b = (theta - std::sin(theta)) / (theta2 * theta);
  }
  const Mat3 P = Hat(phi);
  return Mat3::Identity() - a * P + b * P * P;
}

/// Inverse right Jacobian: JrInv = I + ½Φ + (1/θ² − cos(θ/2)/(2θ sin(θ/2))) Φ².
/// (The half-angle form of (1+cosθ)/(2θ sinθ) stays finite at θ = π; singular at θ = 2π.)
inline Mat3 RightJacobianInverse(const Vec3& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  double c = 0.0;
  if (theta < kTaylorAngle) {
    c = 1.0 / 12.0 + theta2 / 720.0 + theta2 * theta2 / 30240.0;
  } else {
    const double half = 0.5 * theta;
    c = 1.0 / theta2 - std::cos(half) / (2.0 * theta * std::sin(half));
  }
  const Mat3 P = Hat(phi);
  return Mat3::Identity() + 0.5 * P + c * P * P;
}

/// Left Jacobian of SO(3): Exp(phi + δ) ≈ Exp(Jl(phi) δ) Exp(phi); Jl(phi) = Jr(−phi).
inline Mat3 LeftJacobian(const Vec3& phi) { return RightJacobian(-phi); }

/// Inverse left Jacobian, JlInv(phi) = JrInv(−phi).
inline Mat3 LeftJacobianInverse(const Vec3& phi) { return RightJacobianInverse(-phi); }

/// SE(3) exponential of xi = [rho; phi].
inline Eigen::Isometry3d ExpSE3(const Vec6& xi) {
  const Vec3 rho = xi.head<3>();
  const Vec3 phi = xi.tail<3>();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Exp(phi);
  T.translation() = LeftJacobian(phi) * rho;
  return T;
}

/// SE(3) logarithm, xi = [rho; phi] with |phi| ≤ π.
inline Vec6 LogSE3(const Eigen::Isometry3d& T) {
  const Vec3 phi = Log(T.linear());
  Vec6 xi;
  xi.head<3>() = LeftJacobianInverse(phi) * T.translation();
  xi.tail<3>() = phi;
  return xi;
}

/// Adjoint of T for xi = [rho; phi]: T Exp(xi) T⁻¹ = Exp(Adjoint(T) xi).
inline Mat6 Adjoint(const Eigen::Isometry3d& T) {
  const Mat3 R = T.linear();
  Mat6 A = Mat6::Zero();
  A.topLeftCorner<3, 3>() = R;
  A.topRightCorner<3, 3>() = Hat(T.translation()) * R;
  A.bottomRightCorner<3, 3>() = R;
  return A;
}

/// The same rotation with w ≥ 0 (unique representative for comparisons and output).
inline Eigen::Quaterniond PositiveW(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond r = q;
  if (r.w() < 0.0) r.coeffs() = -r.coeffs();
  return r;
}

/// Matrix L(q) with (q ⊗ p).wxyz = L(q) p.wxyz (Hamilton product, w first).
inline Eigen::Matrix4d QuatLeftMatrix(const Eigen::Quaterniond& q) {
  Eigen::Matrix4d m;
  m(0, 0) = q.w();
  m.block<1, 3>(0, 1) = -q.vec().transpose();
  m.block<3, 1>(1, 0) = q.vec();
  m.block<3, 3>(1, 1) = q.w() * Mat3::Identity() + Hat(q.vec());
  return m;
}

/// Matrix R(p) with (q ⊗ p).wxyz = R(p) q.wxyz (Hamilton product, w first).
inline Eigen::Matrix4d QuatRightMatrix(const Eigen::Quaterniond& p) {
  Eigen::Matrix4d m;
  m(0, 0) = p.w();
  m.block<1, 3>(0, 1) = -p.vec().transpose();
  m.block<3, 1>(1, 0) = p.vec();
  m.block<3, 3>(1, 1) = p.w() * Mat3::Identity() - Hat(p.vec());
  return m;
}

/// Rotation from roll, pitch, yaw (rad), R = Rz(yaw) · Ry(pitch) · Rx(roll) (ZYX, intrinsic).
inline Eigen::Quaterniond QuatFromRpy(double roll, double pitch, double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) *
                            Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                            Eigen::AngleAxisd(roll, Vec3::UnitX()));
}

/// Inverse of QuatFromRpy: [roll, pitch, yaw] (rad), pitch ∈ [−π/2, π/2].
inline Vec3 RpyFromRotation(const Mat3& R) {
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  return Vec3(roll, pitch, yaw);
}

}  // namespace swlio::lie

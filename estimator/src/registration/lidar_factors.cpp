// PointToPlaneFactor and PointToLineFactor: both are a fixed k×3 projection A of the feature's
// world position w = R (R_e x + t_e) + p, so they share the Jacobian code (maths in the headers).

#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/registration/point_to_line_factor.h"
#include "swlio/estimator/registration/point_to_plane_factor.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

struct WorldPoint {
  Eigen::Isometry3d T_world_imu;
  Eigen::Isometry3d T_imu_lidar;
  Vec3 y_imu;    ///< R_e x + t_e
  Vec3 w_world;  ///< R y + p
};

WorldPoint Transform(double const* const* parameters, const Vec3& x_lidar) {
  WorldPoint wp;
  wp.T_world_imu = PoseFromParameters(parameters[0]);
  wp.T_imu_lidar = PoseFromParameters(parameters[1]);
  wp.y_imu = wp.T_imu_lidar * x_lidar;
  wp.w_world = wp.T_world_imu * wp.y_imu;
  return wp;
}

// Writes the ambient Jacobians of r = A (w − c) for the blocks Ceres asks for.
template <int K>
void WriteJacobians(const Eigen::Matrix<double, K, 3>& A,
                    const WorldPoint& wp,
                    const Vec3& x_lidar,
                    double const* const* parameters,
                    double** jacobians) {
  using JDelta = Eigen::Matrix<double, K, kPoseTangentSize>;
  using JAmbient = Eigen::Matrix<double, K, kPoseSize, Eigen::RowMajor>;
  const Mat3 R = wp.T_world_imu.linear();
  if (jacobians[0] != nullptr) {
    JDelta J;
    J.template leftCols<3>() = A;
    J.template rightCols<3>() = -A * R * lie::Hat(wp.y_imu);
    Eigen::Map<JAmbient>{jacobians[0]} = J * PoseMinusJacobianAt(parameters[0]);
  }
  if (jacobians[1] != nullptr) {
    const Eigen::Matrix<double, K, 3> AR = A * R;
    JDelta J;
    J.template leftCols<3>() = AR;
    J.template rightCols<3>() = -AR * wp.T_imu_lidar.linear() * lie::Hat(x_lidar);
    Eigen::Map<JAmbient>{jacobians[1]} = J * PoseMinusJacobianAt(parameters[1]);
  }
}

bool ValidWeight(double s) { return std::isfinite(s) && s > 0.0; }

}  // namespace

std::unique_ptr<PointToPlaneFactor> PointToPlaneFactor::Create(const Vec3& point_lidar,
                                                               const Vec3& normal_world,
                                                               const Vec3& centroid_world,
                                                               double sqrt_information) {
  const double n = normal_world.norm();
  if (!(n > 0.0) || !std::isfinite(n) || !ValidWeight(sqrt_information)) return nullptr;
  return std::unique_ptr<PointToPlaneFactor>(
      new PointToPlaneFactor(point_lidar, normal_world / n, centroid_world, sqrt_information));
}

PointToPlaneFactor::PointToPlaneFactor(const Vec3& point_lidar,
                                       const Vec3& normal_world,
                                       const Vec3& centroid_world,
                                       double sqrt_information)
    : point_lidar_(point_lidar),
      normal_world_(normal_world),
      centroid_world_(centroid_world),
      sqrt_information_(sqrt_information) {}

bool PointToPlaneFactor::Evaluate(double const* const* parameters,
                                  double* residuals,
                                  double** jacobians) const {
  const WorldPoint wp = Transform(parameters, point_lidar_);
  const Eigen::Matrix<double, 1, 3> A = sqrt_information_ * normal_world_.transpose();
  residuals[0] = A * (wp.w_world - centroid_world_);
  if (jacobians != nullptr) WriteJacobians<1>(A, wp, point_lidar_, parameters, jacobians);
  return true;
}

std::unique_ptr<PointToLineFactor> PointToLineFactor::Create(const Vec3& point_lidar,
                                                             const Vec3& direction_world,
                                                             const Vec3& centroid_world,
                                                             double sqrt_information) {
  const double n = direction_world.norm();
  if (!(n > 0.0) || !std::isfinite(n) || !ValidWeight(sqrt_information)) return nullptr;
  const Vec3 d = direction_world / n;
  // b₁: d × (the axis least aligned with d), b₂ = d × b₁.
  Eigen::Index axis = 0;
  d.cwiseAbs().minCoeff(&axis);
  const Vec3 b1 = d.cross(Vec3::Unit(axis)).normalized();
  const Vec3 b2 = d.cross(b1);
  Eigen::Matrix<double, 2, 3> basis_t;
  basis_t.row(0) = sqrt_information * b1.transpose();
  basis_t.row(1) = sqrt_information * b2.transpose();
  return std::unique_ptr<PointToLineFactor>(
      new PointToLineFactor(point_lidar, basis_t, centroid_world));
}

PointToLineFactor::PointToLineFactor(const Vec3& point_lidar,
                                     const Eigen::Matrix<double, 2, 3>& basis_t,
                                     const Vec3& centroid_world)
    : point_lidar_(point_lidar), basis_t_(basis_t), centroid_world_(centroid_world) {}

bool PointToLineFactor::Evaluate(double const* const* parameters,
                                 double* residuals,
                                 double** jacobians) const {
  const WorldPoint wp = Transform(parameters, point_lidar_);
  Eigen::Map<Eigen::Vector2d>{residuals} = basis_t_ * (wp.w_world - centroid_world_);
  if (jacobians != nullptr) WriteJacobians<2>(basis_t_, wp, point_lidar_, parameters, jacobians);
  return true;
}

}  // namespace swlio::estimator

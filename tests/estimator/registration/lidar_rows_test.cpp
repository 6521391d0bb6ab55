#include "swlio/estimator/registration/lidar_rows.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

namespace swlio::estimator {
namespace {

/// A random symmetric positive definite H = Q diag(λ) Qᵀ with the given eigenvalues.
Eigen::MatrixXd Spd(const Eigen::VectorXd& lambda, std::mt19937* rng, Eigen::MatrixXd* Q) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd A(lambda.size(), lambda.size());
  for (Eigen::Index i = 0; i < A.size(); ++i) A(i) = n(*rng);
  *Q = Eigen::HouseholderQR<Eigen::MatrixXd>(A).householderQ();
  return *Q * lambda.asDiagonal() * Q->transpose();
}

double Quadratic(const Eigen::MatrixXd& H, const Eigen::VectorXd& b, const Eigen::VectorXd& d) {
  return 0.5 * d.dot(H * d) + b.dot(d);
}

TEST(LidarRows, WithoutAFloorTheRowsReproduceTheQuadraticUpToAConstant) {
  std::mt19937 rng(1);
  Eigen::MatrixXd Q;
  Eigen::VectorXd lambda(6);
  lambda << 3e2, 5e2, 1e3, 4e4, 9e4, 2e5;
  const Eigen::MatrixXd H = Spd(lambda, &rng, &Q);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6, -3.0, 2.0);
  const LidarRows rows = CompressToRows(H, b, Eigen::MatrixXd::Zero(6, 6), 1.0);
  ASSERT_EQ(rows.U.rows(), 6);
  EXPECT_EQ(rows.degenerate, 0);
  const Eigen::VectorXd d0 = Eigen::VectorXd::Zero(6);
  const double c = 0.5 * rows.r0.squaredNorm() - Quadratic(H, b, d0);
  for (int k = 0; k < 5; ++k) {
    const Eigen::VectorXd d = Eigen::VectorXd::Random(6) * 0.1;
    const double rows_cost = 0.5 * (rows.r0 + rows.U * d).squaredNorm();
    EXPECT_NEAR(rows_cost - c, Quadratic(H, b, d), 1e-6 * (1.0 + std::abs(rows_cost)));
  }
}

TEST(LidarRows, DegenerateDirectionsCarryNoInformation) {
  std::mt19937 rng(2);
  Eigen::MatrixXd Q;
  Eigen::VectorXd lambda(6);
  lambda << 0.5, 2.0, 1e3, 4e4, 9e4, 2e5;  // two directions below the threshold of 10
  const Eigen::MatrixXd H = Spd(lambda, &rng, &Q);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(6);
  const LidarRows rows = CompressToRows(H, b, Eigen::MatrixXd::Zero(6, 6), 10.0);
  EXPECT_EQ(rows.degenerate, 2);
  ASSERT_EQ(rows.U.rows(), 4);
  EXPECT_LT((rows.U * Q.col(0)).norm(), 1e-9);
  EXPECT_LT((rows.U * Q.col(1)).norm(), 1e-9);
  EXPECT_GT((rows.U * Q.col(5)).norm(), 1.0);
}

TEST(LidarRows, TheFloorCapsTheInformationAndKeepsTheOptimum) {
  std::mt19937 rng(3);
  Eigen::MatrixXd Q;
  Eigen::VectorXd lambda(6);
  lambda << 1e4, 2e4, 5e4, 1e5, 1e6, 1e7;  // σ from 1e-2 down to 3e-4
  const Eigen::MatrixXd H = Spd(lambda, &rng, &Q);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6, 1.0, 6.0);
  const double floor_sigma = 0.01;
  const Eigen::MatrixXd F = Eigen::MatrixXd::Identity(6, 6) * floor_sigma * floor_sigma;
  const LidarRows rows = CompressToRows(H, b, F, 1.0);
  ASSERT_EQ(rows.U.rows(), 6);
  const Eigen::MatrixXd covariance = (rows.U.transpose() * rows.U).inverse();
  const Eigen::VectorXd sd = covariance.diagonal().cwiseSqrt();
  EXPECT_GE(sd.minCoeff(), floor_sigma * (1.0 - 1e-9)) << "no axis more certain than the floor";
  EXPECT_TRUE(covariance.isApprox(H.inverse() + F, 1e-9));
  // The rows' minimum is the LiDAR optimum δ* = −H⁻¹b.
  const Eigen::VectorXd optimum = -rows.U.colPivHouseholderQr().solve(rows.r0);
  EXPECT_TRUE(optimum.isApprox(-H.inverse() * b, 1e-9));
}

TEST(LidarRows, AllDegenerateGivesNoRows) {
  const LidarRows rows = CompressToRows(Eigen::MatrixXd::Identity(6, 6) * 1e-3,
                                        Eigen::VectorXd::Zero(6), Eigen::MatrixXd::Zero(6, 6), 1.0);
  EXPECT_EQ(rows.U.rows(), 0);
  EXPECT_EQ(rows.degenerate, 6);
}

}  // namespace
}  // namespace swlio::estimator

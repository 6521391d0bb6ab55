// swlio_eval_lib: Umeyama alignment, Sim(3)/SE(3)/origin-aligned APE and rotation errors, on
// synthetic trajectories whose errors are derived by hand in the comments.

#include "swlio/eval/alignment.h"
#include "swlio/eval/evaluate.h"
#include "swlio/eval/metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <random>

namespace swlio::eval {
namespace {

Pose MakePose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Pose T = Pose::Identity();
  T.block<3, 3>(0, 0) = R;
  T.block<3, 1>(0, 3) = t;
  return T;
}

Eigen::Matrix3d Rot(double angle_rad, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle_rad, axis.normalized()).matrix();
}

/// A curved 3D trajectory with changing orientation.
Trajectory Helix(int n) {
  Trajectory t;
  for (int i = 0; i < n; ++i) {
    const double a = 0.1 * i;
    t.poses.push_back(MakePose(Rot(a, Eigen::Vector3d(0.2, 0.1, 1.0)),
                               Eigen::Vector3d(5 * std::cos(a), 3 * std::sin(a), 0.05 * i)));
    t.stamps_s.push_back(0.1 * i);
  }
  return t;
}

TEST(EvalUmeyama, RecoversKnownSim3AndSe3) {
  std::mt19937 rng(42);
  std::normal_distribution<double> g(0.0, 3.0);
  Eigen::Matrix3Xd x(3, 50);
  for (Eigen::Index c = 0; c < x.cols(); ++c) x.col(c) << g(rng), g(rng), g(rng);
  const Eigen::Matrix3d R = Rot(0.7, Eigen::Vector3d(1, -2, 0.5));
  const Eigen::Vector3d t(10, -4, 2.5);
  const double s = 2.5;
  const Eigen::Matrix3Xd y_sim = (s * R * x).colwise() + t;
  const Sim3Transform sim = Umeyama(x, y_sim, true);
  EXPECT_TRUE(sim.R.isApprox(R, 1e-12));
  EXPECT_TRUE(sim.t.isApprox(t, 1e-12));
  EXPECT_NEAR(sim.scale, s, 1e-12);

  const Eigen::Matrix3Xd y_se3 = (R * x).colwise() + t;
  const Sim3Transform se3 = Umeyama(x, y_se3, false);
  EXPECT_TRUE(se3.R.isApprox(R, 1e-12));
  EXPECT_TRUE(se3.t.isApprox(t, 1e-12));
  EXPECT_EQ(se3.scale, 1.0);
}

TEST(EvalUmeyama, NeverReturnsAReflectionAndRejectsDegenerateInput) {
  Eigen::Matrix3Xd x(3, 4);
  x << 1, 0, 0, 1, 0, 2, 0, 1, 0, 0, 3, 1;
  const Eigen::Matrix3Xd mirrored = Eigen::Vector3d(1, 1, -1).asDiagonal() * x;
  const Sim3Transform r = Umeyama(x, mirrored, false);
  EXPECT_NEAR(r.R.determinant(), 1.0, 1e-12);

  Eigen::Matrix3Xd same(3, 5);
  same.colwise() = Eigen::Vector3d(1, 2, 3);
  EXPECT_THROW(Umeyama(same, same, false), EvalError);
  Eigen::Matrix3Xd line(3, 5);
  for (Eigen::Index c = 0; c < 5; ++c) line.col(c) = Eigen::Vector3d(1, 2, 3) * double(c);
  EXPECT_THROW(Umeyama(line, line, true), EvalError);  // rank 1, as evo refuses
  EXPECT_THROW(Umeyama(x, Eigen::Matrix3Xd(3, 3), true), EvalError);
}

// Box corners y_i = c + (±a, ±b, ±cz) and perturbations e_i = h·sx·sy·sz·v, which have zero
// mean and zero cross-covariance with y. With x = G⁻¹(y + e) for G = (s, R, t):
// - SE(3) (s = 1): the fit recovers R, t exactly, so the aligned error is e_i: ‖e_i‖ = h‖v‖.
// - Sim(3): the fit gives scale c = s·tr(C)/(tr(C) + h²‖v‖²) (C = cov of y), so with
//   k = tr(C)/(tr(C) + h²‖v‖²) the aligned point is ȳ + k(y_i − ȳ + e_i) and the error is
//   ‖(k − 1)(y_i − ȳ) + k e_i‖.
struct BoxCase {
  Trajectory ref, est;
  std::vector<Eigen::Vector3d> dy, e;  // y_i − ȳ and e_i
  double k = 0.0;
};

BoxCase MakeBox(double s) {
  const Eigen::Vector3d center(3, -1, 2), half(4, 2, 1), v(0.3, -0.2, 0.1);
  const double h = 0.5;
  const Eigen::Matrix3d R = Rot(0.4, Eigen::Vector3d(0, 1, 1));
  const Eigen::Vector3d t(-2, 5, 1);
  BoxCase b;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d sign(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
    const Eigen::Vector3d dy = sign.cwiseProduct(half);
    const Eigen::Vector3d e = h * sign.prod() * v;
    b.ref.poses.push_back(MakePose(Eigen::Matrix3d::Identity(), center + dy));
    b.est.poses.push_back(
        MakePose(Eigen::Matrix3d::Identity(), R.transpose() * (center + dy + e - t) / s));
    b.dy.push_back(dy);
    b.e.push_back(e);
  }
  const double tr_c = half.squaredNorm();  // (1/8) Σ ‖y_i − ȳ‖²
  b.k = tr_c / (tr_c + h * h * v.squaredNorm());
  return b;
}

TEST(EvalApe, Se3AlignedErrorIsThePerturbation) {
  BoxCase b = MakeBox(1.0);
  const Evaluation r = EvaluateApe({b.ref, b.est}, {Alignment::kSe3, PoseRelation::kTranslation});
  ASSERT_EQ(r.errors.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_NEAR(r.errors[i], b.e[i].norm(), 1e-12);
}

TEST(EvalApe, Sim3AlignedErrorMatchesClosedForm) {
  const double s = 0.37;
  BoxCase b = MakeBox(s);
  const Evaluation r = EvaluateApe({b.ref, b.est}, {Alignment::kSim3, PoseRelation::kTranslation});
  EXPECT_NEAR(r.alignment.scale, s * b.k, 1e-12);
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_NEAR(r.errors[i], ((b.k - 1.0) * b.dy[i] + b.k * b.e[i]).norm(), 1e-12);
  }
  // SE(3) cannot undo the scale: the errors stay large.
  const Evaluation se3 = EvaluateApe({b.ref, b.est}, {Alignment::kSe3, PoseRelation::kTranslation});
  EXPECT_GT(se3.stats.mean, 1.0);
}

TEST(EvalApe, Sim3UndoesAnExactSimilarityOfAWholeTrajectory) {
  const Trajectory ref = Helix(80);
  Trajectory est = ref;
  const Eigen::Matrix3d R = Rot(2.0, Eigen::Vector3d(1, 1, 0));
  for (Pose& P : est.poses) {
    P = MakePose(R * P.block<3, 3>(0, 0), 0.2 * R * P.block<3, 1>(0, 3) + Eigen::Vector3d(1, 2, 3));
  }
  const Evaluation r = EvaluateApe({ref, est}, {Alignment::kSim3, PoseRelation::kTranslation});
  EXPECT_NEAR(r.alignment.scale, 5.0, 1e-9);
  EXPECT_LT(r.stats.max, 1e-9);
  const Evaluation angle = EvaluateApe({ref, est}, {Alignment::kSim3, PoseRelation::kAngleDeg});
  EXPECT_LT(angle.stats.max, 1e-6);
}

TEST(EvalApe, RotationAngleInDegreesIsThePerturbationAngle) {
  // est_i = ref_i · Rot(θ_i, a_i): E_i = est_i⁻¹ ref_i = Rot(−θ_i, a_i), angle θ_i.
  const Trajectory ref = Helix(6);
  const std::vector<double> theta_deg = {0.0, 1e-4, 0.5, 30.0, 120.0, 179.0};
  Trajectory est = ref;
  for (std::size_t i = 0; i < est.Size(); ++i) {
    const Eigen::Vector3d axis(1.0 + double(i), -2.0, 0.5 * double(i));
    est.poses[i] = ref.poses[i] * MakePose(Rot(theta_deg[i] * std::numbers::pi / 180, axis),
                                           Eigen::Vector3d::Zero());
  }
  const std::vector<double> deg = ApeErrors(ref, est, PoseRelation::kAngleDeg);
  const std::vector<double> rad = ApeErrors(ref, est, PoseRelation::kAngleRad);
  for (std::size_t i = 0; i < est.Size(); ++i) {
    EXPECT_NEAR(deg[i], theta_deg[i], 1e-9) << i;
    EXPECT_NEAR(rad[i], theta_deg[i] * std::numbers::pi / 180, 1e-11) << i;
  }
  // Translations are untouched by a right-multiplied rotation.
  for (double e : ApeErrors(ref, est, PoseRelation::kTranslation)) EXPECT_EQ(e, 0.0);
}

TEST(EvalApe, OriginAlignmentMakesTheFirstPosesCoincide) {
  // est_i = T_off · ref_i · D_i with D_0 = I: after origin alignment est_i = ref_i D_i, so the
  // translation error is ‖d_i‖ and the angle that of D_i.
  const Trajectory ref = Helix(5);
  const Pose T_off = MakePose(Rot(1.0, Eigen::Vector3d(0, 0, 1)), Eigen::Vector3d(7, 8, 9));
  std::vector<Pose> D;
  for (int i = 0; i < 5; ++i) {
    D.push_back(MakePose(Rot(0.01 * i, Eigen::Vector3d(1, 0, 0)), Eigen::Vector3d(0.1 * i, 0, 0)));
  }
  Trajectory est = ref;
  for (std::size_t i = 0; i < 5; ++i) est.poses[i] = T_off * ref.poses[i] * D[i];
  const Evaluation t = EvaluateApe({ref, est}, {Alignment::kOrigin, PoseRelation::kTranslation});
  const Evaluation a = EvaluateApe({ref, est}, {Alignment::kOrigin, PoseRelation::kAngleRad});
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(t.errors[i], 0.1 * double(i), 1e-12);
    EXPECT_NEAR(a.errors[i], 0.01 * double(i), 1e-12);
  }
  const Evaluation none = EvaluateApe({ref, est}, {Alignment::kNone, PoseRelation::kTranslation});
  EXPECT_GT(none.stats.min, 5.0);  // the 7-8-9 m offset is still there
}

}  // namespace
}  // namespace swlio::eval

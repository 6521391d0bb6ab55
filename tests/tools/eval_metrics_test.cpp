// swlio_eval_lib: statistics, RPE pairs and errors (frames and metres), KITTI metric, on
// synthetic trajectories with errors derived by hand in the comments.

#include "swlio/eval/evaluate.h"
#include "swlio/eval/kitti_metric.h"
#include "swlio/eval/metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace swlio::eval {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Pose MakePose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Pose T = Pose::Identity();
  T.block<3, 3>(0, 0) = R;
  T.block<3, 1>(0, 3) = t;
  return T;
}

Eigen::Matrix3d Rz(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).matrix();
}

Trajectory FromPositions(const std::vector<Eigen::Vector3d>& p) {
  Trajectory t;
  for (const auto& x : p) t.poses.push_back(MakePose(Eigen::Matrix3d::Identity(), x));
  return t;
}

TEST(EvalStatistics, MatchesHandComputedValues) {
  const std::vector<double> even = {4.0, 1.0, 3.0, 2.0};
  const Statistics s = ComputeStatistics(even);
  EXPECT_EQ(s.n, 4u);
  EXPECT_EQ(s.max, 4.0);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);  // mean of the middle two
  EXPECT_DOUBLE_EQ(s.sse, 30.0);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population (ddof 0): (2.25+0.25+0.25+2.25)/4
  const std::vector<double> odd = {5.0, 1.0, 2.0};
  EXPECT_EQ(ComputeStatistics(odd).median, 2.0);
  EXPECT_THROW(ComputeStatistics(std::vector<double>{}), EvalError);
}

TEST(EvalRpe, FrameDeltaPairsAndTranslationErrors) {
  // Identity rotations: Q_i = (i, 0, 0), P_i = (1.1 i, 0.2 i², 0), so for a pair (i, j)
  // E_t = P_j − P_i − (Q_j − Q_i) = (0.1 (j − i), 0.2 (j² − i²), 0).
  std::vector<Eigen::Vector3d> q, p;
  for (int i = 0; i < 7; ++i) {
    q.emplace_back(i, 0, 0);
    p.emplace_back(1.1 * i, 0.2 * i * i, 0);
  }
  const RpeResult r =
      Rpe(FromPositions(q), FromPositions(p), 2, DeltaUnit::kFrames, PoseRelation::kTranslation);
  const IdPairs expected_pairs = {{0, 2}, {2, 4}, {4, 6}};
  ASSERT_EQ(r.pairs, expected_pairs);
  for (std::size_t k = 0; k < r.pairs.size(); ++k) {
    const double i = double(r.pairs[k].first), j = double(r.pairs[k].second);
    EXPECT_NEAR(r.errors[k], std::hypot(0.1 * (j - i), 0.2 * (j * j - i * i)), 1e-12);
  }
  // Delta 1 (evo's default): every consecutive pair.
  EXPECT_EQ(RpePairs(FromPositions(q), 1, DeltaUnit::kFrames).size(), 6u);
}

TEST(EvalRpe, FrameDeltaRotationErrorsInDegrees) {
  // Q_i = Rz(10° i), P_i = Rz(12° i), no translation: E = Rz(−10°Δ) Rz(12°Δ) = Rz(2°Δ).
  Trajectory ref, est;
  for (int i = 0; i < 10; ++i) {
    ref.poses.push_back(MakePose(Rz(10 * kDeg * i), Eigen::Vector3d::Zero()));
    est.poses.push_back(MakePose(Rz(12 * kDeg * i), Eigen::Vector3d::Zero()));
  }
  const RpeResult deg = Rpe(ref, est, 3, DeltaUnit::kFrames, PoseRelation::kAngleDeg);
  ASSERT_EQ(deg.pairs.size(), 3u);  // ids 0, 3, 6, 9
  for (double e : deg.errors) EXPECT_NEAR(e, 6.0, 1e-10);
  // ‖Rz(φ) − I‖_F = 2√2 sin(φ/2) for both the full and the rotation-part relations.
  const double expected = 2.0 * std::sqrt(2.0) * std::sin(3.0 * kDeg);
  for (PoseRelation rel : {PoseRelation::kFull, PoseRelation::kRotationPart}) {
    for (double e : Rpe(ref, est, 3, DeltaUnit::kFrames, rel).errors)
      EXPECT_NEAR(e, expected, 1e-12);
  }
  for (double e : Rpe(ref, est, 3, DeltaUnit::kFrames, PoseRelation::kTranslation).errors) {
    EXPECT_EQ(e, 0.0);
  }
}

TEST(EvalRpe, MetreDeltaPairsArePickedOnTheEstimate) {
  // Estimate steps 0.5 m, reference steps 0.25 m along x. With δ = 1 m the estimate's path sum
  // reaches 1.0 at ids 2, 4, 6, 8 (index 0 never recorded): pairs (2,4), (4,6), (6,8).
  // (On the reference it would be ids 4, 8 and a single pair.) Error per pair: 1.0 − 0.5 m.
  std::vector<Eigen::Vector3d> q, p;
  for (int i = 0; i < 9; ++i) {
    q.emplace_back(0.25 * i, 0, 0);
    p.emplace_back(0.5 * i, 0, 0);
  }
  const RpeResult r =
      Rpe(FromPositions(q), FromPositions(p), 1.0, DeltaUnit::kMeters, PoseRelation::kTranslation);
  const IdPairs expected = {{2, 4}, {4, 6}, {6, 8}};
  EXPECT_EQ(r.pairs, expected);
  for (double e : r.errors) EXPECT_DOUBLE_EQ(e, 0.5);
  const IdPairs on_ref = {{4, 8}};
  EXPECT_EQ(RpePairs(FromPositions(q), 1.0, DeltaUnit::kMeters), on_ref);
}

TEST(EvalRpe, RejectsBadDeltas) {
  const Trajectory t = FromPositions({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
  EXPECT_THROW(RpePairs(t, 0, DeltaUnit::kFrames), EvalError);
  EXPECT_THROW(RpePairs(t, 1.5, DeltaUnit::kFrames), EvalError);
  EXPECT_THROW(RpePairs(t, 3, DeltaUnit::kFrames), EvalError);  // no pair fits
  EXPECT_THROW(RpePairs(t, -1.0, DeltaUnit::kMeters), EvalError);
  EXPECT_THROW(RpePairs(t, 5.0, DeltaUnit::kMeters), EvalError);
}

TEST(EvalRpe, PipelineAlignsBeforePickingMetrePairs) {
  // Sim(3) alignment rescales the estimate (half size) before its path is walked: the pairs
  // then equal those of the reference.
  std::vector<Eigen::Vector3d> q, p;
  for (int i = 0; i < 41; ++i) {
    const double a = 0.2 * i;
    q.emplace_back(10 * std::cos(a), 10 * std::sin(a), 0.1 * i);
    p.emplace_back(20 * std::cos(a), 20 * std::sin(a), 0.2 * i);
  }
  RpeOptions options;
  options.alignment = Alignment::kSim3;
  options.delta = 5.0;
  options.delta_unit = DeltaUnit::kMeters;
  const Evaluation r = EvaluateRpe({FromPositions(q), FromPositions(p)}, options);
  EXPECT_NEAR(r.alignment.scale, 0.5, 1e-12);
  const IdPairs ref_pairs = RpePairs(FromPositions(q), 5.0, DeltaUnit::kMeters);
  ASSERT_EQ(r.errors.size(), ref_pairs.size());
  for (std::size_t k = 0; k < ref_pairs.size(); ++k) {
    EXPECT_EQ(r.error_pose_ids[k], ref_pairs[k].second);
  }
  EXPECT_LT(r.stats.max, 1e-9);
}

// KITTI metric on a straight line with 1 m per frame: with integer path distances the devkit's
// last frame for (first f, length L) is f + L + 1 (first distance strictly beyond L).
TEST(EvalKitti, ScaleErrorGivesKnownTranslationPercent) {
  // est = 1.01 × gt: the error of a segment is 0.01 (L + 1) m, divided by the nominal L.
  Trajectory gt, est;
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    gt.poses.push_back(MakePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, i)));
    est.poses.push_back(MakePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 1.01 * i)));
  }
  const KittiResult r = KittiOdometryMetric(gt, est);
  double sum = 0.0;
  std::size_t count = 0;
  for (int f = 0; f < n; f += 10) {
    for (int L = 100; L <= 800; L += 100) {
      if (f + L + 1 >= n) continue;
      sum += 0.01 * (L + 1) / L;
      ++count;
    }
  }
  ASSERT_EQ(r.segments.size(), count);
  EXPECT_EQ(r.segments.front().last_frame, 101u);
  EXPECT_NEAR(r.t_err_percent, 100.0 * sum / double(count), 1e-9);
  EXPECT_NEAR(r.per_length.front().t_err_percent, 1.01, 1e-9);
  EXPECT_NEAR(r.r_err_deg_per_100m, 0.0, 1e-9);
}

TEST(EvalKitti, YawDriftGivesKnownRotationError) {
  // est_i = (Rz(α i), gt position): along z, the segment rotation error is α (L + 1), the
  // translation error 0; per 100 m in degrees: α (L + 1) / L · 180/π · 100.
  const double alpha = 0.001;
  Trajectory gt, est;
  for (int i = 0; i < 300; ++i) {
    gt.poses.push_back(MakePose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, i)));
    est.poses.push_back(MakePose(Rz(alpha * i), Eigen::Vector3d(0, 0, i)));
  }
  const KittiResult r = KittiOdometryMetric(gt, est);
  ASSERT_EQ(r.per_length.size(), 2u);  // only 100 and 200 m fit in 299 m
  EXPECT_NEAR(r.per_length[0].r_err_deg_per_100m, alpha * 101 / 100 / kDeg * 100, 1e-6);
  EXPECT_NEAR(r.per_length[1].r_err_deg_per_100m, alpha * 201 / 200 / kDeg * 100, 1e-6);
  EXPECT_NEAR(r.t_err_percent, 0.0, 1e-9);
  EXPECT_THROW(KittiOdometryMetric(gt, Trajectory{}), EvalError);
}

}  // namespace
}  // namespace swlio::eval

// swlio_eval_lib: trajectory file parsing (valid and malformed) and time association.

#include "swlio/eval/association.h"
#include "swlio/eval/evaluate.h"
#include "swlio/eval/json.h"
#include "swlio/eval/trajectory.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>

namespace swlio::eval {
namespace {

/// The EvalError message of `fn`, or "" when it does not throw.
template <typename Fn>
std::string ErrorOf(Fn&& fn) {
  try {
    fn();
  } catch (const EvalError& e) {
    return e.what();
  }
  return "";
}

TEST(EvalIo, ParsesTumWithCommentsAndNormalisesQuaternions) {
  std::istringstream in(
      "# timestamp tx ty tz qx qy qz qw\n"
      "\n"
      "1.5 1 2 3 0 0 0 2\n"  // non-unit quaternion: identity after normalising
      "1.6,4,5,6,0,0,0.7071067811865476,0.7071067811865476\n");  // commas, 90° about z
  const Trajectory t = ParseTum(in, "mem");
  ASSERT_EQ(t.Size(), 2u);
  EXPECT_EQ(t.stamps_s[0], 1.5);
  EXPECT_EQ(t.Position(0), Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE((t.poses[0].block<3, 3>(0, 0).isApprox(Eigen::Matrix3d::Identity(), 1e-15)));
  const Eigen::Vector3d x_rotated = t.poses[1].block<3, 3>(0, 0) * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(x_rotated.isApprox(Eigen::Vector3d::UnitY(), 1e-12));
}

TEST(EvalIo, ParsesKittiRowMajor) {
  std::istringstream in("1 0 0 10 0 1 0 20 0 0 1 30\n0 -1 0 1 1 0 0 2 0 0 1 3\n");
  const Trajectory t = ParseKitti(in, "mem");
  ASSERT_EQ(t.Size(), 2u);
  EXPECT_FALSE(t.HasStamps());
  EXPECT_EQ(t.Position(0), Eigen::Vector3d(10, 20, 30));
  EXPECT_EQ(t.poses[1](0, 1), -1.0);
  EXPECT_EQ(t.poses[1](1, 0), 1.0);
  EXPECT_EQ(t.poses[1].row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

TEST(EvalIo, WriteThenReadRoundTrips) {
  Trajectory t;
  for (int i = 0; i < 5; ++i) {
    Pose T = Pose::Identity();
    T.block<3, 3>(0, 0) =
        Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    T.block<3, 1>(0, 3) = Eigen::Vector3d(0.1 * i, -2.0 / 3.0 * i, 1e-3 * i);
    t.poses.push_back(T);
    t.stamps_s.push_back(1e9 + 0.1 * i);
  }
  std::stringstream tum;
  WriteTum(tum, t);
  const Trajectory back = ParseTum(tum, "tum");
  std::stringstream kitti;
  WriteKitti(kitti, t);
  const Trajectory back_k = ParseKitti(kitti, "kitti");
  ASSERT_EQ(back.Size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(back.stamps_s[i], t.stamps_s[i]);
    EXPECT_TRUE(back.poses[i].isApprox(t.poses[i], 1e-14));
    EXPECT_EQ(back_k.poses[i], t.poses[i]);  // %.17g round-trips exactly
  }
}

TEST(EvalIo, MalformedTumLinesNameFileAndLine) {
  std::istringstream short_line("# c\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
  EXPECT_EQ(ErrorOf([&] { ParseTum(short_line, "a.tum"); }),
            "a.tum:3: expected 8 numbers (timestamp tx ty tz qx qy qz qw), got 7");
  std::istringstream word("1 0 0 0 0 0 0 1\n2 0 x 0 0 0 0 1\n");
  EXPECT_EQ(ErrorOf([&] { ParseTum(word, "b.tum"); }), "b.tum:2: field 3 ('x') is not a number");
  std::istringstream nan("1 0 0 nan 0 0 0 1\n");
  EXPECT_EQ(ErrorOf([&] { ParseTum(nan, "c.tum"); }), "c.tum:1: field 4 is not finite");
  std::istringstream zero_q("1 0 0 0 0 0 0 0\n");
  EXPECT_EQ(ErrorOf([&] { ParseTum(zero_q, "d.tum"); }), "d.tum:1: quaternion has zero norm");
  std::istringstream trailing("1 0 0 0 0 0 0 1x\n");
  EXPECT_EQ(ErrorOf([&] { ParseTum(trailing, "e.tum"); }),
            "e.tum:1: field 8 ('1x') is not a number");
  std::istringstream empty("# only a comment\n\n");
  EXPECT_EQ(ErrorOf([&] { ParseTum(empty, "f.tum"); }), "f.tum: no poses");
}

TEST(EvalIo, MalformedKittiAndTimesFilesNameFileAndLine) {
  std::istringstream eleven("1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n");
  EXPECT_EQ(ErrorOf([&] { ParseKitti(eleven, "p.txt"); }),
            "p.txt:2: expected 12 numbers (3×4 pose matrix, row-major), got 11");
  std::istringstream times("0.0\n0.1 0.2\n");
  EXPECT_EQ(ErrorOf([&] { ParseTimes(times, "t.txt"); }),
            "t.txt:2: expected 1 number (time in seconds), got 2");

  const auto dir = test::MakeTempDir("eval_io");
  std::ofstream(dir / "p.txt") << "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n";
  std::ofstream(dir / "t.txt") << "0\n0.1\n0.2\n";
  EXPECT_EQ(
      ErrorOf([&] { ReadKittiFile(dir / "p.txt", dir / "t.txt"); }),
      (dir / "t.txt").string() + ": has 3 times but " + (dir / "p.txt").string() + " has 2 poses");
  EXPECT_EQ(ErrorOf([&] { ReadTumFile(dir / "missing.tum"); }),
            (dir / "missing.tum").string() + ": cannot open file");
  std::filesystem::remove_all(dir);
}

TEST(EvalAssociation, NearestStampWithinToleranceFromShorterTrajectory) {
  // Reference at 10 Hz; estimate (shorter) with jitter, one stamp 15 ms away from any reference.
  const std::vector<double> ref = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5};
  const std::vector<double> est = {0.004, 0.196, 0.315, 0.509};
  const Association a = AssociateByTime(ref, est, {0.01, 0.0});
  EXPECT_EQ(a.ref_ids, (std::vector<std::size_t>{0, 2, 5}));
  EXPECT_EQ(a.est_ids, (std::vector<std::size_t>{0, 1, 3}));

  // A wider tolerance keeps the 15 ms pair too.
  const Association wide = AssociateByTime(ref, est, {0.02, 0.0});
  EXPECT_EQ(wide.ref_ids, (std::vector<std::size_t>{0, 2, 3, 5}));

  // An offset of +0.1 s on the estimate shifts every match by one reference sample.
  const Association shifted = AssociateByTime(ref, est, {0.01, 0.1});
  EXPECT_EQ(shifted.ref_ids, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(shifted.est_ids, (std::vector<std::size_t>{0, 1}));

  EXPECT_NE(ErrorOf([&] { AssociateByTime(ref, {5.0, 6.0}, {0.01, 0.0}); }), "");
}

TEST(EvalAssociation, LongerEstimateIsSearchedAndMayBeReused) {
  // The reference is the shorter one here: each reference stamp takes its nearest estimate.
  const std::vector<double> ref = {1.0, 1.002};
  const std::vector<double> est = {0.99, 0.999, 1.0005, 1.1};
  const Association a = AssociateByTime(ref, est, {0.01, 0.0});
  EXPECT_EQ(a.ref_ids, (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(a.est_ids, (std::vector<std::size_t>{2, 2}));  // both nearest to 1.0005
}

TEST(EvalAssociation, TiesTakeTheFirstIndexAndUnsortedStampsMatchSorted) {
  // 0.5 is equally far from 0.25 and 0.75 (exact binary values): the first index wins.
  const Association tie = NearestStamps({0.5}, {0.25, 0.75}, 1.0, 0.0);
  EXPECT_EQ(tie.est_ids, (std::vector<std::size_t>{0}));
  const Association dup = NearestStamps({0.8}, {0.25, 0.75, 0.75}, 1.0, 0.0);  // past the end
  EXPECT_EQ(dup.est_ids, (std::vector<std::size_t>{1}));

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::vector<double> target(200), query(150);
  for (double& t : target) t = u(rng);
  for (double& t : query) t = u(rng);
  std::vector<double> sorted = target;
  std::sort(sorted.begin(), sorted.end());
  const Association from_sorted = NearestStamps(query, sorted, 0.02, 0.0);
  const Association from_unsorted = NearestStamps(query, target, 0.02, 0.0);
  ASSERT_EQ(from_sorted.ref_ids, from_unsorted.ref_ids);
  ASSERT_FALSE(from_sorted.ref_ids.empty());
  for (std::size_t k = 0; k < from_sorted.est_ids.size(); ++k) {
    EXPECT_EQ(sorted[from_sorted.est_ids[k]], target[from_unsorted.est_ids[k]]);
  }
}

TEST(EvalAssociation, KittiPairingNeedsEqualCounts) {
  Trajectory a, b;
  a.poses.assign(3, Pose::Identity());
  b.poses.assign(2, Pose::Identity());
  EXPECT_EQ(ErrorOf([&] { Pair(a, b, Format::kKitti); }),
            "KITTI trajectories must have the same number of poses (reference 3, estimate 2)");
}

TEST(EvalJson, StatisticsRoundTripExactlyWithTheIssueKeys) {
  Statistics s;
  s.n = 3;
  s.max = 1.0 / 3.0;
  s.mean = 0.1;
  s.median = 2.0 / 7.0;
  s.min = 1e-300;
  s.rmse = 12345.678901234567;
  s.sse = 7715.0734402916314;
  s.std = 0.6002822693967811;
  const std::string json = ToJson(s);
  const std::vector<std::pair<std::string, double>> expected = {
      {"max", s.max},   {"mean", s.mean}, {"median", s.median}, {"min", s.min},
      {"rmse", s.rmse}, {"sse", s.sse},   {"std", s.std}};
  EXPECT_EQ(json.rfind("{\"n\": 3, \"max\": ", 0), 0u) << json;
  for (const auto& [key, value] : expected) {
    const std::string tag = "\"" + key + "\": ";
    const auto at = json.find(tag);
    ASSERT_NE(at, std::string::npos) << key;
    EXPECT_EQ(std::strtod(json.c_str() + at + tag.size(), nullptr), value) << key;
  }
  EXPECT_EQ(json.back(), '}');
}

}  // namespace
}  // namespace swlio::eval

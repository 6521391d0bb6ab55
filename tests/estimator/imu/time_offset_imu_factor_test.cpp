// TimeOffsetImuFactor: with the offset the samples really had, the residual of an interval
// integrated at the wrong offset comes back to (nearly) that of the right one.

#include "swlio/estimator/imu/time_offset_imu_factor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <iostream>
#include <memory>
#include <vector>

#include "sim_imu_util.h"
#include "swlio/core/time.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"
#include "swlio/estimator/imu/time_shift_jacobian.h"

namespace swlio::estimator {
namespace {

constexpr double kG = 9.80665;
using Vec15 = Eigen::Matrix<double, kImuFactorResiduals, 1>;

struct Blocks {
  std::array<double, kPoseSize> pose_i{}, pose_j{};
  std::array<double, kSpeedBiasSize> sb_i{}, sb_j{};
  std::array<double, kGravityTiltSize> tilt{};
  double offset_s = 0.0;
};

Blocks TrueBlocks(const sim::Trajectory& trajectory, int64_t t_i, int64_t t_j) {
  Blocks b;
  const State si = test::TrueState(trajectory, t_i);
  const State sj = test::TrueState(trajectory, t_j);
  PoseToParameters(si.T_world_imu, b.pose_i.data());
  PoseToParameters(sj.T_world_imu, b.pose_j.data());
  Eigen::Map<Eigen::Vector3d>(&b.sb_i[kSbVel]) = si.vel_world;
  Eigen::Map<Eigen::Vector3d>(&b.sb_j[kSbVel]) = sj.vel_world;
  return b;
}

/// The interval's first and last samples as the pre-integration holds them (at its bounds).
std::pair<ImuSample, ImuSample> Ends(const std::vector<ImuSample>& imu, int64_t t_i, int64_t t_j) {
  const auto at = [&](int64_t t) {
    return *std::lower_bound(imu.begin(), imu.end(), t,
                             [](const ImuSample& s, int64_t v) { return s.t_ns < v; });
  };
  return {at(t_i), at(t_j)};
}

struct Interval {
  std::unique_ptr<ImuFactor> imu;
  Vec9 J = Vec9::Zero();
};

Interval Integrate(const std::vector<ImuSample>& imu, int64_t t_i, int64_t t_j) {
  Interval out;
  ImuNoiseConfig noise;
  Preintegrator pre(noise, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(pre.Integrate(imu, t_i, t_j), PreintegrationStatus::kOk);
  const auto [first, last] = Ends(imu, t_i, t_j);
  out.J = TimeShiftJacobian(pre.result(), first, last);
  out.imu = ImuFactor::Create(pre.result(), noise, kG);
  return out;
}

Vec15 Residual(const ceres::CostFunction& f, Blocks& b, bool with_tilt) {
  std::vector<const double*> p = {b.pose_i.data(), b.sb_i.data(), b.pose_j.data(), b.sb_j.data()};
  if (with_tilt) p.push_back(b.tilt.data());
  p.push_back(&b.offset_s);
  Vec15 r;
  EXPECT_TRUE(f.Evaluate(p.data(), r.data(), nullptr));
  return r;
}

TEST(TimeOffsetImuFactor, TheTrueOffsetUndoesTheShiftOfTheSamples) {
  sim::SimSetup setup = *sim::MakeSimSetup("aggressive", 5, 30.0);
  test::MakeNoiseFree(setup);
  const std::vector<ImuSample> truth =
      test::ToImuSamples(sim::SimulateImu(*setup.trajectory, setup.imu, 5));
  // The IMU's stamps 4 ms late, integrated as they are (applied offset 0).
  const double offset_s = 4e-3;
  std::vector<ImuSample> late = truth;
  for (ImuSample& s : late) s.t_ns += SecToNs(offset_s);
  double worst_ratio = 0.0, signal = 0.0;
  for (double t0 = 3.0; t0 < 27.0; t0 += 1.3) {
    const int64_t t_i = SecToNs(t0), t_j = SecToNs(t0 + 0.1);
    const Interval right = Integrate(truth, t_i, t_j);
    const Interval wrong = Integrate(late, t_i, t_j);
    ASSERT_NE(right.imu, nullptr);
    ASSERT_NE(wrong.imu, nullptr);
    Blocks b = TrueBlocks(*setup.trajectory, t_i, t_j);
    const TimeOffsetImuFactor at_right(right.imu.get(), *right.imu, right.J, 0.0);
    const TimeOffsetImuFactor at_wrong(wrong.imu.get(), *wrong.imu, wrong.J, 0.0);
    b.offset_s = 0.0;
    const double r_right = Residual(at_right, b, false).norm();
    const double r_uncorrected = Residual(at_wrong, b, false).norm();
    b.offset_s = offset_s;
    const double r_corrected = Residual(at_wrong, b, false).norm();
    signal = std::max(signal, r_uncorrected);
    // Where the shift shows (its rates change), first order takes most of it away.
    if (r_uncorrected > 1.0) worst_ratio = std::max(worst_ratio, r_corrected / r_uncorrected);
    EXPECT_LT(r_right, 0.05);  // noise-free: the true states fit the right integration (σ units)
  }
  std::cout << "largest uncorrected whitened residual " << signal
            << ", worst corrected/uncorrected " << worst_ratio << "\n";
  EXPECT_GT(signal, 10.0);  // the shift shows, many σ
  EXPECT_GT(worst_ratio, 0.0);
  EXPECT_LT(worst_ratio, 0.2);
}

TEST(TimeOffsetImuFactor, AddsOneBlockAndItsJacobianToTheInnerFactor) {
  sim::SimSetup setup = *sim::MakeSimSetup("aggressive", 5, 10.0);
  test::MakeNoiseFree(setup);
  const std::vector<ImuSample> imu =
      test::ToImuSamples(sim::SimulateImu(*setup.trajectory, setup.imu, 5));
  const int64_t t_i = SecToNs(4.0), t_j = SecToNs(4.1);
  const Interval in = Integrate(imu, t_i, t_j);
  ASSERT_NE(in.imu, nullptr);
  const GravityTiltImuFactor tilt(in.imu.get());
  const double applied_s = 2e-3;
  const TimeOffsetImuFactor f(&tilt, *in.imu, in.J, applied_s);
  ASSERT_EQ(f.parameter_block_sizes().size(), 6U);
  EXPECT_EQ(f.parameter_block_sizes().back(), 1);
  EXPECT_EQ(f.num_residuals(), kImuFactorResiduals);

  Blocks b = TrueBlocks(*setup.trajectory, t_i, t_j);
  b.tilt = {1e-3, -2e-3};
  b.offset_s = applied_s;  // no correction: the inner factor's residual
  std::vector<const double*> p = {b.pose_i.data(), b.sb_i.data(), b.pose_j.data(),
                                  b.sb_j.data(),   b.tilt.data(), &b.offset_s};
  Vec15 inner_r, r;
  ASSERT_TRUE(tilt.Evaluate(p.data(), inner_r.data(), nullptr));
  ASSERT_TRUE(f.Evaluate(p.data(), r.data(), nullptr));
  EXPECT_LT((r - inner_r).norm(), 1e-12);

  // ∂r/∂d against a central difference, and the inner blocks' Jacobians passed through.
  b.offset_s = applied_s + 1e-3;
  std::vector<double> jac_pose_i(kImuFactorResiduals * kPoseSize);
  Vec15 jac_d;
  std::array<double*, 6> jacobians = {jac_pose_i.data(), nullptr, nullptr,
                                      nullptr,           nullptr, jac_d.data()};
  ASSERT_TRUE(f.Evaluate(p.data(), r.data(), jacobians.data()));
  const double h = 1e-5;
  b.offset_s += h;
  Vec15 r_plus;
  ASSERT_TRUE(f.Evaluate(p.data(), r_plus.data(), nullptr));
  b.offset_s -= 2 * h;
  Vec15 r_minus;
  ASSERT_TRUE(f.Evaluate(p.data(), r_minus.data(), nullptr));
  const Vec15 numeric = (r_plus - r_minus) / (2 * h);
  EXPECT_GT(jac_d.norm(), 0.0);
  EXPECT_LT((numeric - jac_d).norm(), 1e-6 * jac_d.norm());
  std::vector<double> inner_pose_i(kImuFactorResiduals * kPoseSize);
  std::array<double*, 5> inner_jacobians = {inner_pose_i.data(), nullptr, nullptr, nullptr,
                                            nullptr};
  ASSERT_TRUE(tilt.Evaluate(p.data(), inner_r.data(), inner_jacobians.data()));
  EXPECT_EQ(jac_pose_i, inner_pose_i);
}

}  // namespace
}  // namespace swlio::estimator

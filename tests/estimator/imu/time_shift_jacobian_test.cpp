// TimeShiftJacobian against pre-integrations of the same motion with every sample time moved.

#include "swlio/estimator/imu/time_shift_jacobian.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <vector>

#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {
namespace {

/// [δφ; δv; δp] of the interval integrated with every stamp earlier by shift_ns (the samples
/// then cover [t_i + shift, t_j + shift]) against the unshifted one.
Vec9 ShiftedMinusNominal(const std::vector<ImuSample>& imu,
                         int64_t t_i,
                         int64_t t_j,
                         int64_t shift_ns) {
  std::vector<ImuSample> shifted = imu;
  for (ImuSample& s : shifted) s.t_ns -= shift_ns;
  const ImuNoiseConfig noise;
  Preintegrator a(noise, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  Preintegrator b(noise, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(a.Integrate(imu, t_i, t_j), PreintegrationStatus::kOk);
  EXPECT_EQ(b.Integrate(shifted, t_i, t_j), PreintegrationStatus::kOk);
  Vec9 d;
  d.segment<3>(kRowR) = lie::Log(a.result().delta_R.transpose() * b.result().delta_R);
  d.segment<3>(kRowV) = b.result().delta_v - a.result().delta_v;
  d.segment<3>(kRowP) = b.result().delta_p - a.result().delta_p;
  return d;
}

/// The interval's first and last samples as the pre-integration holds them (at its bounds).
std::pair<ImuSample, ImuSample> Ends(const std::vector<ImuSample>& imu, int64_t t_i, int64_t t_j) {
  const auto at = [&](int64_t t) {
    const auto it = std::lower_bound(imu.begin(), imu.end(), t,
                                     [](const ImuSample& s, int64_t v) { return s.t_ns < v; });
    return *it;
  };
  return {at(t_i), at(t_j)};
}

TEST(TimeShiftJacobian, MatchesShiftedIntegrationOnAggressiveMotion) {
  sim::SimSetup setup = *sim::MakeSimSetup("aggressive", 5, 30.0);
  test::MakeNoiseFree(setup);
  const std::vector<ImuSample> imu =
      test::ToImuSamples(sim::SimulateImu(*setup.trajectory, setup.imu, 5));
  const double eps_s = 2e-3;
  double worst = 0.0, signal = 0.0;
  for (double t0 = 3.0; t0 < 27.0; t0 += 1.3) {
    const int64_t t_i = SecToNs(t0), t_j = SecToNs(t0 + 0.1);
    Preintegrator pre(ImuNoiseConfig{}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    ASSERT_EQ(pre.Integrate(imu, t_i, t_j), PreintegrationStatus::kOk);
    const auto [first, last] = Ends(imu, t_i, t_j);
    const Vec9 predicted = TimeShiftJacobian(pre.result(), first, last) * eps_s;
    const Vec9 measured = ShiftedMinusNominal(imu, t_i, t_j, SecToNs(eps_s));
    worst = std::max(worst, (predicted - measured).norm() / (measured.norm() + 1e-6));
    signal = std::max(signal, measured.segment<3>(kRowR).norm());
  }
  EXPECT_GT(signal, 1e-4);  // the motion changes its rate: a shift shows
  EXPECT_LT(worst, 0.1);    // first order within 10 %
  std::cout << "worst relative error " << worst << "\n";
}

TEST(TimeShiftJacobian, UncertaintyAddsAlongTheJacobianOnly) {
  PreintegratedImu pim;
  pim.covariance = Mat9::Identity() * 1e-8;
  Vec9 J = Vec9::Zero();
  J(kRowR + 2) = 0.5;
  const PreintegratedImu out = WithTimeOffsetUncertainty(pim, J, 4e-3);
  EXPECT_NEAR(out.covariance(kRowR + 2, kRowR + 2), 1e-8 + 0.25 * 16e-6, 1e-12);
  EXPECT_DOUBLE_EQ(out.covariance(0, 0), 1e-8);
  EXPECT_EQ(WithTimeOffsetUncertainty(pim, J, 0.0).covariance, pim.covariance);
}

}  // namespace
}  // namespace swlio::estimator

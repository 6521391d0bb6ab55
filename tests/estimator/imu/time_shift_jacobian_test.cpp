// TimeShiftJacobian against pre-integrations of the same motion with every sample time moved.

#include "swlio/estimator/imu/time_shift_jacobian.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>
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

/// The samples within [t_i, t_j], as the window's interval holds them (one-sided at its ends).
std::vector<ImuSample> Interval(const std::vector<ImuSample>& imu, int64_t t_i, int64_t t_j) {
  std::vector<ImuSample> out;
  for (const ImuSample& s : imu)
    if (s.t_ns >= t_i && s.t_ns <= t_j) out.push_back(s);
  return out;
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
    const std::vector<ImuSample> interval = Interval(imu, t_i, t_j);
    const Vec9 predicted =
        TimeShiftJacobian(pre.result(), EndRates(interval, t_i), EndRates(interval, t_j)) * eps_s;
    const Vec9 measured = ShiftedMinusNominal(imu, t_i, t_j, SecToNs(eps_s));
    worst = std::max(worst, (predicted - measured).norm() / (measured.norm() + 1e-6));
    signal = std::max(signal, measured.segment<3>(kRowR).norm());
  }
  EXPECT_GT(signal, 1e-4);  // the motion changes its rate: a shift shows
  EXPECT_LT(worst, 0.1);    // first order within 10 %
  std::cout << "worst relative error " << worst << "\n";
}

// A line through the samples near an end: exact on a steady change, and a quarter or so of one
// sample's noise variance at 400 Hz (16 samples: (4·16 − 2) / (16·17) = 0.23).
TEST(TimeShiftJacobian, EndRatesFollowATrendWithLessNoiseThanOneSample) {
  const int64_t dt_ns = 2'500'000, t_end_ns = 100'000'000;
  const auto rate = [](int64_t t) {
    return Eigen::Vector3d(Eigen::Vector3d(0.1, -0.2, 0.3) +
                           2.0 * NsToSec(t) * Eigen::Vector3d::Ones());
  };
  const auto force = [](int64_t t) {
    return Eigen::Vector3d(Eigen::Vector3d(1.0, 0.0, 9.8) -
                           5.0 * NsToSec(t) * Eigen::Vector3d::UnitX());
  };
  std::vector<ImuSample> ramp;  // each sample the mean over its interval: the middle's value
  for (int64_t t = 0; t <= t_end_ns; t += dt_ns) {
    ImuSample s;
    s.t_ns = t;
    s.gyro_radps = rate(t - dt_ns / 2);
    s.acc_mps2 = force(t - dt_ns / 2);
    ramp.push_back(s);
  }
  for (const int64_t t : {int64_t{0}, t_end_ns}) {
    const ImuSample fit = EndRates(ramp, t);
    EXPECT_LT((fit.gyro_radps - rate(t)).norm(), 1e-9);
    EXPECT_LT((fit.acc_mps2 - force(t)).norm(), 1e-9);
    EXPECT_EQ(fit.t_ns, t);
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  double sq = 0.0;
  int n = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<ImuSample> noisy = ramp;
    for (ImuSample& s : noisy) s.gyro_radps.x() += noise(rng);
    const double err = EndRates(noisy, t_end_ns).gyro_radps.x() - rate(t_end_ns).x();
    sq += err * err;
    ++n;
  }
  const double variance_ratio = sq / n;  // one sample's variance is 1
  EXPECT_GT(variance_ratio, 0.15);
  EXPECT_LT(variance_ratio, 0.32);
  std::cout << "end-rate variance / one sample's: " << variance_ratio << "\n";
  // Too few samples near the end: the nearest one.
  const std::vector<ImuSample> two(ramp.begin(), ramp.begin() + 2);
  EXPECT_EQ(EndRates(two, 0).gyro_radps, ramp.front().gyro_radps);
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

TEST(TimeShiftJacobian, UncertaintyWidensTheRotationAlone) {
  PreintegratedImu pim;
  pim.covariance = Mat9::Identity() * 1e-8;
  Vec9 J = Vec9::Zero();
  J(kRowR + 0) = 0.3;
  J(kRowR + 1) = -0.4;
  J(kRowV + 2) = 2.0;  // a bump's change of specific force
  J(kRowP + 0) = 0.1;
  const PreintegratedImu out = WithTimeOffsetUncertainty(pim, J, 5e-3);
  EXPECT_NEAR(out.covariance(kRowR + 0, kRowR + 1), 25e-6 * 0.3 * -0.4, 1e-15);
  EXPECT_NEAR(out.covariance(kRowR + 1, kRowR + 1), 1e-8 + 25e-6 * 0.16, 1e-15);
  const Mat9 added = out.covariance - pim.covariance;
  EXPECT_TRUE(added.bottomRows<6>().isZero(0.0)) << added;  // velocity and position rows
  EXPECT_TRUE(added.rightCols<6>().isZero(0.0)) << added;
}

}  // namespace
}  // namespace swlio::estimator

// EstimatorRunner's sync rule: a sweep is processed once an IMU sample past its end has arrived
// — at once when one already has, else with that sample — in order, and never twice.

#include "swlio/daemon/pipeline/estimator_runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {
namespace {

ImuSample Still(int64_t t_ns) {
  ImuSample s;
  s.t_ns = t_ns;
  s.acc_mps2 = Eigen::Vector3d(0.0, 0.0, 9.80665);
  return s;
}

Scan Sweep(int64_t end_ns) {
  Scan s;
  s.t_start_ns = end_ns - 100'000'000;
  s.t_end_ns = end_ns;
  return s;
}

TEST(EstimatorRunner, ProcessesASweepOnceTheImuHasPassedItsEnd) {
  DaemonConfig config;
  const EstimatorSetup setup =
      MakeEstimatorSetup(config, Eigen::Isometry3d::Identity(), EstimatorMode::kTightlyCoupled);
  std::vector<int64_t> processed;
  EstimatorRunner runner(setup, nullptr, [&](const Scan& scan, const estimator::WindowResult&) {
    processed.push_back(scan.t_end_ns);
  });
  constexpr int64_t kMs = 1'000'000;
  for (int64_t t = 0; t <= 500 * kMs; t += 2'500'000) runner.AddImu(Still(t));
  runner.AddScan(Sweep(400 * kMs));  // the IMU is already past its end (live)
  ASSERT_EQ(processed, (std::vector<int64_t>{400 * kMs}));
  runner.AddScan(Sweep(600 * kMs));  // not yet covered (replay order)
  runner.AddScan(Sweep(700 * kMs));
  EXPECT_EQ(processed.size(), 1u);
  EXPECT_EQ(runner.waiting(), 2u);
  for (int64_t t = 502'500'000; t <= 600 * kMs; t += 2'500'000) runner.AddImu(Still(t));
  EXPECT_EQ(processed.size(), 1u) << "a sample at the end itself does not cover it";
  runner.AddImu(Still(602'500'000));
  EXPECT_EQ(processed.size(), 1u) << "the cut step's line needs the sample after the holder";
  runner.AddImu(Still(605 * kMs));
  EXPECT_EQ(processed, (std::vector<int64_t>{400 * kMs, 600 * kMs}));
  runner.AddImu(Still(800 * kMs));
  EXPECT_EQ(processed.size(), 2u);
  runner.AddImu(Still(802'500'000));
  EXPECT_EQ(processed, (std::vector<int64_t>{400 * kMs, 600 * kMs, 700 * kMs}));
  EXPECT_EQ(runner.waiting(), 0u);
}

// Five seconds of sweeps arrive while the IMU's bytes wait in the serial layer; then the whole
// backlog arrives. 20 sweeps are kept, the oldest (next to the last state) and the newest
// among them, spread so that the IMU bridges no gap much longer than 50 sweeps / 19 intervals.
TEST(EstimatorRunner, ThinsSweepsThatWaitForALateImuEvenly) {
  DaemonConfig config;
  const EstimatorSetup setup =
      MakeEstimatorSetup(config, Eigen::Isometry3d::Identity(), EstimatorMode::kTightlyCoupled);
  std::vector<int64_t> processed;
  EstimatorRunner runner(setup, nullptr, [&](const Scan& scan, const estimator::WindowResult&) {
    processed.push_back(scan.t_end_ns);
  });
  constexpr int64_t kSweepNs = 100'000'000;
  for (int k = 1; k <= 50; ++k) runner.AddScan(Sweep(int64_t{k} * kSweepNs));  // no IMU yet
  EXPECT_TRUE(processed.empty());
  EXPECT_EQ(runner.waiting(), EstimatorRunner::kMaxWaiting);
  EXPECT_EQ(runner.dropped_waiting(), 50u - EstimatorRunner::kMaxWaiting);
  for (int64_t t = 0; t <= 51 * kSweepNs; t += 2'500'000) runner.AddImu(Still(t));
  ASSERT_EQ(processed.size(), EstimatorRunner::kMaxWaiting);
  EXPECT_EQ(processed.front(), kSweepNs) << "the oldest is kept";
  EXPECT_EQ(processed.back(), 50 * kSweepNs) << "the newest is kept";
  int64_t longest_ns = 0;
  for (size_t i = 1; i < processed.size(); ++i) {
    longest_ns = std::max(longest_ns, processed[i] - processed[i - 1]);
  }
  EXPECT_LE(longest_ns, 4 * kSweepNs) << "49 intervals over 19 is 2.6 sweeps";
}

}  // namespace
}  // namespace swlio::daemon

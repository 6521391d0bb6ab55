// EstimatorRunner's sync rule: a sweep is processed once an IMU sample past its end has arrived
// — at once when one already has, else with that sample — in order, and never twice.

#include "swlio/daemon/pipeline/estimator_runner.h"

#include <gtest/gtest.h>

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
  EXPECT_EQ(processed, (std::vector<int64_t>{400 * kMs, 600 * kMs}));
  runner.AddImu(Still(800 * kMs));
  EXPECT_EQ(processed, (std::vector<int64_t>{400 * kMs, 600 * kMs, 700 * kMs}));
  EXPECT_EQ(runner.waiting(), 0u);
}

TEST(EstimatorRunner, DropsSweepsThatWaitTooLongForTheImu) {
  DaemonConfig config;
  const EstimatorSetup setup =
      MakeEstimatorSetup(config, Eigen::Isometry3d::Identity(), EstimatorMode::kTightlyCoupled);
  size_t processed = 0;
  EstimatorRunner runner(setup, nullptr,
                         [&](const Scan&, const estimator::WindowResult&) { ++processed; });
  for (int k = 1; k <= 25; ++k) runner.AddScan(Sweep(int64_t{k} * 100'000'000));  // no IMU
  EXPECT_EQ(processed, 0u);
  EXPECT_EQ(runner.waiting(), EstimatorRunner::kMaxWaiting);
  EXPECT_EQ(runner.dropped_waiting(), 25u - EstimatorRunner::kMaxWaiting);
}

}  // namespace
}  // namespace swlio::daemon

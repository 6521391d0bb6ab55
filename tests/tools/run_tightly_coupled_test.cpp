// swlio-run --mode tightly-coupled (the default) on a simulated recording: the sliding-window
// LiDAR-IMU estimator follows the simulator's ground truth and reports its stage timings.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sim_recording.h"
#include "sim_setup.h"
#include "swlio/eval/evaluate.h"
#include "test_data.h"

namespace swlio {
namespace {

namespace fs = std::filesystem;

TEST(RunTightlyCoupled, FollowsTheSimulatedDrive) {
  const fs::path tool = test::ToolPath("swlio-run");
  if (tool.empty()) GTEST_SKIP() << "swlio-run not built next to the tests";
  // 25 s of `short`: about 3 s standing (initialization), then ~25 m along the south road.
  const fs::path dir = test::MakeTempDir("swlio_run_tc");
  auto setup = sim::MakeSimSetup("short", 11, 25.0);
  ASSERT_TRUE(setup);
  sim::RecordingStats stats;
  std::string error;
  ASSERT_TRUE(sim::WriteRecording(*setup, dir, &stats, &error)) << error;

  int code = 0;
  // No --mode: tightly coupled is the default.
  const std::string out =
      test::RunCommand(tool.string() + " " + dir.string() + " --out " + (dir / "est.tum").string() +
                           " --timings " + (dir / "t.csv").string() + " 2>&1",
                       &code);
  ASSERT_EQ(code, 0) << out;
  std::ifstream csv(dir / "t.csv");
  std::string line;
  size_t optimized = 0;
  std::getline(csv, line);
  while (std::getline(csv, line)) {
    double f = 0, m = 0, o = 0, tot = 0;
    long long t_ns = 0;
    size_t points = 0;
    if (std::sscanf(line.c_str(), "%lld,%zu,%lf,%lf,%lf,%lf", &t_ns, &points, &f, &m, &o, &tot) ==
            6 &&
        o > 0.0) {
      ++optimized;
    }
  }
  EXPECT_GE(optimized, 200u) << "the window optimization runs on every tracked sweep";

  eval::ApeOptions options;
  options.alignment = eval::Alignment::kSe3;
  const eval::Evaluation ape = eval::EvaluateApe(
      eval::LoadPaired(dir / "groundtruth.tum", dir / "est.tum", eval::Format::kTum), options);
  EXPECT_GE(ape.errors.size(), 200u);
  // LiDAR-only measures 0.02 m here (run_command_test.cpp); the window must not be worse.
  EXPECT_LT(ape.stats.rmse, 0.05) << out;
  EXPECT_LT(ape.stats.max, 0.15) << out;
}

}  // namespace
}  // namespace swlio

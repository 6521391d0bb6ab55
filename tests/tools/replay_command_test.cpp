// swlio-replay as a user runs it on a recording: --deterministic output is byte-identical on two
// runs and equal to swlio-run's (the same decoders, clock models, sync rule and estimator).

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "test_data.h"

namespace swlio {
namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The simulator's `short` drive, its first `seconds`, recorded into `rec`.
::testing::AssertionResult RecordShortDrive(uint64_t seed, double seconds, const fs::path& rec) {
  const auto setup = sim::MakeSimSetup("short", seed, seconds);
  if (!setup) return ::testing::AssertionFailure() << "no simulator setup";
  sim::RecordingStats stats;
  std::string error;
  if (!sim::WriteRecording(*setup, rec, &stats, &error))
    return ::testing::AssertionFailure() << error;
  return ::testing::AssertionSuccess();
}

/// Both tools, found next to the tests (skipped where they are not built).
class ReplayCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    replay = test::ToolPath("swlio-replay");
    run = test::ToolPath("swlio-run");
    if (replay.empty() || run.empty()) GTEST_SKIP() << "swlio-replay / swlio-run not built";
  }
  fs::path replay, run;
};

TEST_F(ReplayCommand, DeterministicReplayIsByteIdenticalAndMatchesSwlioRun) {
  const fs::path dir = test::MakeTempDir("swlio_replay");
  ASSERT_TRUE(RecordShortDrive(11, 10.0, dir / "rec"));
  int code = 0;
  for (const char* name : {"a.tum", "b.tum"}) {
    const std::string out =
        test::RunCommand(replay.string() + " " + (dir / "rec").string() +
                             " --deterministic --out " + (dir / name).string() + " 2>&1",
                         &code);
    ASSERT_EQ(code, 0) << out;
    EXPECT_NE(out.find("\"sweeps\": "), std::string::npos) << out;
  }
  test::RunCommand(run.string() + " " + (dir / "rec").string() + " --out " +
                       (dir / "run.tum").string() + " 2>&1",
                   &code);
  ASSERT_EQ(code, 0);
  const std::string a = ReadAll(dir / "a.tum");
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 50);
  EXPECT_EQ(a, ReadAll(dir / "b.tum"));
  EXPECT_EQ(a, ReadAll(dir / "run.tum"));
}

// A daemon recording made with --time-scale 2 (the simulator at 2×) holds receive times on the
// sensors' time base; the estimator runs on it and both tools write host times, as the daemon
// published them: the same poses as on the unscaled recording, at origin + (t − origin) / 2.
TEST_F(ReplayCommand, BothToolsWriteAScaledRecordingOnHostTime) {
  const fs::path dir = test::MakeTempDir("swlio_replay_scaled");
  ASSERT_TRUE(RecordShortDrive(12, 8.0, dir / "rec"));
  fs::copy(dir / "rec", dir / "rec2");
  const int64_t origin_ns = 1'000'000'000;
  std::ofstream(dir / "rec2" / "manifest.yaml", std::ios::app)
      << "time_scale: 2\ntime_origin_ns: " << origin_ns << "\n";
  int code = 0;
  const auto tool = [&](const fs::path& exe, const char* rec, const char* out) {
    const std::string log = test::RunCommand(exe.string() + " " + (dir / rec).string() +
                                                 (exe == replay ? " --deterministic" : "") +
                                                 " --out " + (dir / out).string() + " 2>&1",
                                             &code);
    EXPECT_EQ(code, 0) << log;
    std::ifstream in(dir / out);
    std::vector<std::pair<double, std::string>> rows;  // stamp (s), pose
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      const size_t space = line.find(' ');
      rows.emplace_back(std::stod(line.substr(0, space)), line.substr(space));
    }
    return rows;
  };
  const auto plain = tool(run, "rec", "plain.tum");
  const auto scaled_run = tool(run, "rec2", "run2.tum");
  const auto scaled_replay = tool(replay, "rec2", "replay2.tum");
  ASSERT_GT(plain.size(), 20u);
  ASSERT_EQ(scaled_run.size(), plain.size());
  ASSERT_EQ(scaled_replay.size(), plain.size());
  const double origin_s = static_cast<double>(origin_ns) * 1e-9;
  for (size_t i = 0; i < plain.size(); ++i) {
    EXPECT_NEAR(scaled_run[i].first, origin_s + (plain[i].first - origin_s) / 2.0, 2e-9) << i;
    EXPECT_EQ(scaled_run[i].second, plain[i].second) << i;
    EXPECT_EQ(scaled_replay[i], scaled_run[i]) << i;
  }
}

TEST_F(ReplayCommand, RefusesAFolderWithoutARecording) {
  const fs::path dir = test::MakeTempDir("swlio_replay_empty");
  int code = 0;
  const std::string out = test::RunCommand(
      replay.string() + " " + dir.string() + " --out " + (dir / "x.tum").string() + " 2>&1", &code);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("neither a recording folder"), std::string::npos) << out;
}

}  // namespace
}  // namespace swlio

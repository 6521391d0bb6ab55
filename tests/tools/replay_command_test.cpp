// swlio-replay as a user runs it on a recording: --deterministic output is byte-identical on two
// runs and equal to swlio-run's (the same decoders, clock models, sync rule and estimator).

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "sim_recording.h"
#include "sim_setup.h"
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

TEST(ReplayCommand, DeterministicReplayIsByteIdenticalAndMatchesSwlioRun) {
  const fs::path replay = test::ToolPath("swlio-replay");
  const fs::path run = test::ToolPath("swlio-run");
  if (replay.empty() || run.empty()) GTEST_SKIP() << "swlio-replay / swlio-run not built";
  const fs::path dir = test::MakeTempDir("swlio_replay");
  const auto setup = sim::MakeSimSetup("short", 11, 10.0);
  ASSERT_TRUE(setup.has_value());
  sim::RecordingStats stats;
  std::string error;
  ASSERT_TRUE(sim::WriteRecording(*setup, dir / "rec", &stats, &error)) << error;
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

TEST(ReplayCommand, RefusesAFolderWithoutARecording) {
  const fs::path replay = test::ToolPath("swlio-replay");
  if (replay.empty()) GTEST_SKIP() << "swlio-replay not built";
  const fs::path dir = test::MakeTempDir("swlio_replay_empty");
  int code = 0;
  const std::string out = test::RunCommand(
      replay.string() + " " + dir.string() + " --out " + (dir / "x.tum").string() + " 2>&1", &code);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("cannot read"), std::string::npos) << out;
}

}  // namespace
}  // namespace swlio

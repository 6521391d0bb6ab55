// swlio-run on a recording whose IMU receive times were delayed by a constant (as
// scripts/shift-imu-rx does, and as the issue measured the cost of an unknown offset): the clock
// model then maps every IMU sample 8 ms later than it was measured, and the window's online
// time-offset estimate must find those 8 ms on top of whatever it finds on the recording as
// written (the clock models' own residual), and report them in the summary and per sweep.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "shared_sim_recording.h"
#include "test_data.h"

namespace swlio {
namespace {

namespace fs = std::filesystem;

/// The number after the first `key` in `out` (NaN if none).
double NumberAfterKey(const std::string& out, const std::string& key) {
  const size_t at = out.find(key);
  return at == std::string::npos ? std::nan("") : std::stod(out.substr(at + key.size()));
}

/// `src` copied to `dst` with imu.rx.csv's t_rx_ns (third column) delayed by `shift_ns`.
void CopyWithImuDelayed(const fs::path& src, const fs::path& dst, int64_t shift_ns) {
  fs::create_directories(dst);
  for (const fs::directory_entry& e : fs::directory_iterator(src)) {
    if (e.path().filename() != "imu.rx.csv") fs::copy(e.path(), dst / e.path().filename());
  }
  std::ifstream in(src / "imu.rx.csv");
  std::ofstream out(dst / "imu.rx.csv");
  std::string line;
  std::getline(in, line);
  out << line << '\n';  // byte_offset,bytes,t_rx_ns
  while (std::getline(in, line)) {
    const size_t comma = line.rfind(',');
    out << line.substr(0, comma + 1) << std::stoll(line.substr(comma + 1)) + shift_ns << '\n';
  }
}

TEST(RunTimeOffset, AnImuDelayedInItsReceiveTimesIsFoundAndReported) {
  const fs::path tool = test::ToolPath("swlio-run");
  if (tool.empty()) GTEST_SKIP() << "swlio-run not built next to the tests";
  std::string error;
  const fs::path recording = test::SharedSimRecording("aggressive", 42, 40.0, &error);
  ASSERT_FALSE(recording.empty()) << error;
  const fs::path dir = test::MakeTempDir("swlio_run_time_offset");
  CopyWithImuDelayed(recording, dir / "delayed", 8'000'000);
  auto run = [&](const fs::path& input, const std::string& tag) {
    int code = 0;
    const std::string out =
        test::RunCommand(tool.string() + " " + input.string() + " --loop-closure off --out " +
                             (dir / (tag + ".tum")).string() + " --diagnostics " +
                             (dir / (tag + ".csv")).string() + " 2>&1",
                         &code);
    EXPECT_EQ(code, 0) << out;
    return out;
  };
  const std::string as_written = run(recording, "as_written");
  const std::string delayed = run(dir / "delayed", "delayed");
  const double base_ms = NumberAfterKey(as_written, "\"applied_ms\": ");
  const double found_ms = NumberAfterKey(delayed, "\"applied_ms\": ");
  // The clock models leave a fraction of a millisecond (the LiDAR's 0.3 ms network latency, the
  // serial frame's transmission time against the one subtracted).
  EXPECT_LT(std::abs(base_ms), 1.0) << as_written;
  EXPECT_NEAR(found_ms - base_ms, 8.0, 0.5) << delayed;
  EXPECT_GT(NumberAfterKey(delayed, "\"updates\": "), 0.0) << delayed;
  EXPECT_LT(NumberAfterKey(delayed, "\"sigma_ms\": "), 0.4) << delayed;
  // Per sweep: the applied offset in the diagnostics' time_offset_ms column.
  std::ifstream csv(dir / "delayed.csv");
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_NE(header.find(",time_offset_ms,time_offset_estimate_ms,time_offset_sigma_ms"),
            std::string::npos)
      << header;
  while (std::getline(csv, line)) last = line;
  EXPECT_NE(last.find(",tracking,"), std::string::npos) << last;
}

}  // namespace
}  // namespace swlio

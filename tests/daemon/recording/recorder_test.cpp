// The recording keeps both clocks (issue 34): manifest.yaml states the published stamps' clock
// and realtime − monotonic at the start; clock_offsets.csv has that offset again and a row at
// each change over 0.1 ms (a wall-clock step), none for smaller wobbles. The clocks are the
// StampClock's, injected.

#include "swlio/daemon/recording/recorder.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kSec = 1'000'000'000;

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// clock_offsets.csv's rows as (t_monotonic_ns, offset_ns), after checking its header.
std::vector<std::pair<int64_t, int64_t>> Rows(const std::filesystem::path& dir) {
  std::ifstream in(dir / "clock_offsets.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t_monotonic_ns,realtime_minus_monotonic_ns");
  std::vector<std::pair<int64_t, int64_t>> out;
  while (std::getline(in, line)) {
    const size_t comma = line.find(',');
    out.emplace_back(std::stoll(line.substr(0, comma)), std::stoll(line.substr(comma + 1)));
  }
  return out;
}

void Sleep() { std::this_thread::sleep_for(std::chrono::milliseconds(60)); }

TEST(Recorder, KeepsTheClockOffsetAtTheStartAndAtEveryStep) {
  std::atomic<int64_t> monotonic_ns{100 * kSec};
  std::atomic<int64_t> realtime_ns{1'780'000'000 * kSec};
  const StampClock stamps(
      true, ClockSources{[&] { return monotonic_ns.load(); }, [&] { return realtime_ns.load(); }});
  const auto dir = test::MakeTempDir("recorder_clock_offsets");
  std::string error;
  auto recorder =
      Recorder::Create(dir, DaemonConfig{}, Eigen::Isometry3d::Identity(), {}, &error, &stamps);
  ASSERT_NE(recorder, nullptr) << error;
  const std::string manifest = ReadText(dir / "manifest.yaml");
  EXPECT_NE(manifest.find("\nstamp_clock: realtime\n"), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\nrealtime_minus_monotonic_ns: 1779999900000000000\n"),
            std::string::npos)
      << manifest;

  std::atomic<bool> stop{false};
  std::thread thread([&] { recorder->Run(stop, Watchdog::Handle{}); });
  Sleep();
  monotonic_ns += kSec;
  realtime_ns += kSec + 50'000;  // 50 µs of slew: no row
  Sleep();
  monotonic_ns += kSec;
  realtime_ns += kSec + 10 * kSec;  // a +10 s step
  Sleep();
  stop = true;
  thread.join();
  const std::vector<std::pair<int64_t, int64_t>> rows = Rows(dir);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], std::make_pair(100 * kSec, 1'779'999'900 * kSec));
  EXPECT_EQ(rows[1],
            std::make_pair(102 * kSec, 1'780'000'000 * kSec - 100 * kSec + 10 * kSec + 50'000));
}

}  // namespace
}  // namespace swlio::daemon

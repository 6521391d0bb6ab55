// Incidents from ring segments (incident_store.h): an event's span, events joining it, the
// keeper writing it once the ring has passed its end, and the count bound removing the oldest
// but never the newest.

#include "swlio/daemon/blackbox/incident_store.h"

#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "swlio/daemon/recording/recording_files.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kSec = 1'000'000'000;
constexpr int64_t kEpoch = 1'780'000'000 * kSec;  // CLOCK_REALTIME of daemon time 0

std::string Read(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Fixture {
  std::filesystem::path dir = test::MakeTempDir("incident_store");
  DaemonConfig config;
  RingSegments ring{dir / "ring"};
  std::unique_ptr<IncidentStore> store;

  explicit Fixture(int64_t max_count = 20) {
    config.record.incident_before_s = 15;
    config.record.incident_after_s = 10;
    config.record.incidents_max_count = max_count;
    store = std::make_unique<IncidentStore>(dir / "incidents", &ring, config.record, "9.9 (test)");
  }
  /// A ring segment over [t_s, t_s + 10) with one log line.
  void Segment(int64_t t_s) {
    RecordingSetup setup;
    setup.config = &config;
    std::string error;
    const std::filesystem::path d = ring.NextDir();
    auto f = RecordingFiles::Open(d, setup, {}, &error);
    ASSERT_NE(f, nullptr) << error;
    f->LogLine("segment " + std::to_string(t_s));
    ASSERT_TRUE(f->Close());
    ring.Add({d, t_s * kSec, (t_s + 10) * kSec, DirectoryBytes(d)});
    store->OnSegmentClosed((t_s + 10) * kSec);
  }
  void Event(int64_t t_s, const std::string& reason) {
    store->OnEvent({t_s * kSec, kEpoch + t_s * kSec, reason, reason + " detail \"quoted\""});
  }
  /// Runs the keeper until every incident is written.
  void Keep() {
    std::atomic<bool> stop{true};
    store->Run(stop, Watchdog::Handle{});
  }
  std::vector<std::string> Incidents() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir / "incidents"))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

TEST(IncidentStore, KeepsTheSpanAroundTheEventWithTheEventsThatJoinedIt) {
  Fixture f;
  for (int64_t t = 0; t < 40; t += 10) f.Segment(t);
  f.Event(42, "lidar_silent");  // span [27, 52]
  f.Event(45, "divergence");    // joins it
  EXPECT_EQ(f.store->KeepFromNs(), 27 * kSec);
  f.Segment(40);  // ends at 50: not yet past 52
  f.Keep();
  EXPECT_TRUE(f.Incidents().empty());
  f.Segment(50);  // ends at 60
  f.Keep();
  ASSERT_EQ(f.Incidents(), std::vector<std::string>{"20260528T202722Z-lidar_silent"});
  const auto inc = f.dir / "incidents" / f.Incidents()[0];
  const std::string yaml = Read(inc / "incident.yaml");
  EXPECT_NE(yaml.find("reason: lidar_silent\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("swlio_version: \"9.9 (test)\""), std::string::npos) << yaml;
  // Whole segments [20, 60) cover the asked [27, 52].
  EXPECT_NE(yaml.find("span: {start_ns: 20000000000, end_ns: 60000000000"), std::string::npos)
      << yaml;
  EXPECT_NE(yaml.find("cut_short: false"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("reason: divergence, detail: \"divergence detail \\\"quoted\\\"\""),
            std::string::npos)
      << yaml;
  EXPECT_EQ(Read(inc / "log.txt"), "segment 20\nsegment 30\nsegment 40\nsegment 50\n");
  EXPECT_EQ(f.store->KeepFromNs(), INT64_MAX);
  EXPECT_EQ(f.store->counters().kept, 1u);
}

TEST(IncidentStore, AStopCutsTheOpenIncidentShort) {
  Fixture f;
  f.Segment(0);
  f.Event(5, "imu_silent");
  f.store->CloseAll();
  f.Keep();
  ASSERT_EQ(f.Incidents().size(), 1u);
  const std::string yaml = Read(f.dir / "incidents" / f.Incidents()[0] / "incident.yaml");
  EXPECT_NE(yaml.find("cut_short: true"), std::string::npos) << yaml;
}

TEST(IncidentStore, TheCountBoundRemovesTheOldestNeverTheNewest) {
  Fixture f(/*max_count=*/2);
  for (int64_t i = 0; i < 4; ++i) {
    const int64_t t = i * 100;
    f.Segment(t);
    f.Event(t + 5, "clock_jump");
    f.Segment(t + 10);
    f.Segment(t + 20);
    f.Keep();
  }
  const std::vector<std::string> names = f.Incidents();
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[0], "20260528T203005Z-clock_jump");  // t = 205
  EXPECT_EQ(names[1], "20260528T203145Z-clock_jump");  // t = 305, the newest
  EXPECT_EQ(f.store->counters().removed, 2u);
}

TEST(IncidentStore, AnIncidentWhoseSegmentsAreGoneFailsWithItsReason) {
  Fixture f;
  f.Event(5, "watchdog");
  f.Segment(100);  // past the span, but no segment overlaps [−10, 15]
  f.Keep();
  EXPECT_TRUE(f.Incidents().empty());
  EXPECT_EQ(f.store->counters().failed, 1u);
  EXPECT_NE(f.store->counters().last_error.find("no ring segment"), std::string::npos);
}

}  // namespace
}  // namespace swlio::daemon

// The black box's recorder (recorder.h, record.ring): segments rotate and stay within their
// bounds; a full disk stops the ring but never the threads that feed it; an earlier run that
// did not stop cleanly leaves an incident.

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <array>
#include <fstream>
#include <thread>

#include "swlio/daemon/recording/recorder.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using namespace std::chrono_literals;

struct Ring {
  DaemonConfig config;
  std::unique_ptr<Recorder> recorder;
  std::string error;

  explicit Ring(const std::filesystem::path& dir) {
    config.record.ring = true;
    config.record.directory = dir.string();
    config.record.segment_s = 1.0;
    config.record.ring_minutes = 0.05;  // 3 s
    config.record.incident_before_s = 1.0;
    config.record.incident_after_s = 1.0;
  }
  bool Create() {
    RecordingSetup setup;
    setup.config = &config;
    setup.time = TimeScale{MonotonicNowNs(), 1.0};
    setup.version = "test";
    recorder = Recorder::CreateRing(setup, &error);
    return recorder != nullptr;
  }
};

/// Feeds `n` LiDAR datagrams of 1248 bytes over `period` each; counts refused pushes.
uint64_t Feed(Recorder* r, int n, std::chrono::microseconds period) {
  uint64_t refused = 0;
  LidarPacket p;
  p.size = 1248;
  for (int i = 0; i < n; ++i) {
    p.t_rx_ns = MonotonicNowNs();
    refused += r->lidar_queue().Push(p) ? 0 : 1;
    std::this_thread::sleep_for(period);
  }
  return refused;
}

TEST(RecorderRing, SegmentsRotateAndTheOldGo) {
  const auto dir = test::MakeTempDir("recorder_ring");
  Ring ring(dir);
  ASSERT_TRUE(ring.Create()) << ring.error;
  std::atomic<bool> stop{false};
  std::thread t([&] { ring.recorder->Run(stop, Watchdog::Handle{}); });
  EXPECT_EQ(Feed(ring.recorder.get(), 2500, 2ms), 0u);  // ≥ 5 s at 500 datagrams/s
  stop = true;
  t.join();
  const RecorderCounters c = ring.recorder->counters();
  EXPECT_FALSE(c.stopped) << c.error;
  EXPECT_EQ(c.lidar_packets, 2500u);
  EXPECT_GE(c.segments_deleted, 1u);  // 3 s of ring, ≥ 5 s recorded
  EXPECT_LE(c.segments, 5u);
  EXPECT_TRUE(std::filesystem::exists(dir / "ring" / kCleanStopMark));
  size_t folders = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "ring")) {
    if (!e.is_directory()) continue;
    ++folders;
    for (const char* f : {"lidar.pcap", "imu.xbus", "imu.rx.csv", "health.csv", "log.txt",
                          "odometry.tum", "manifest.yaml", "config.yaml", "clock_offsets.csv"})
      EXPECT_TRUE(std::filesystem::exists(e.path() / f)) << e.path() << " " << f;
  }
  EXPECT_EQ(folders, c.segments);
}

TEST(RecorderRing, AFullDiskStopsTheRingAndNothingElse) {
  if (geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
  const auto dir = test::MakeTempDir("recorder_full_disk");
  if (mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=256k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
  {
    Ring ring(dir);
    ring.config.record.max_disk_mb = 100;  // the disk fills first
    ASSERT_TRUE(ring.Create()) << ring.error;
    std::atomic<bool> stop{false};
    std::thread t([&] { ring.recorder->Run(stop, Watchdog::Handle{}); });
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(Feed(ring.recorder.get(), 1500, 1ms), 0u) << "the producer must never be refused";
    const double fed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stop = true;
    t.join();
    const RecorderCounters c = ring.recorder->counters();
    EXPECT_TRUE(c.stopped);
    EXPECT_NE(c.error.find("No space left on device"), std::string::npos) << c.error;
    EXPECT_GT(c.discarded, 0u);
    EXPECT_LT(fed_s, 10.0);  // a loose sanity bound: 1.5 s of pushes were never held up
    EXPECT_TRUE(std::filesystem::exists(dir / "ring" / kCleanStopMark))
        << "a stop after a full disk is still a clean stop";
    std::cout << "[ note ] " << c.error << "; " << c.discarded << " datagrams discarded\n";
  }
  umount2(dir.c_str(), MNT_DETACH);
}

/// A ring folder as an earlier run left it, with one log line.
void Leftover(const std::filesystem::path& ring_dir, const DaemonConfig& config) {
  RecordingSetup setup;
  setup.config = &config;
  std::string error;
  auto f = RecordingFiles::Open(ring_dir / "seg-000004", setup, {}, &error);
  ASSERT_NE(f, nullptr) << error;
  f->LogLine("the last words");
  ASSERT_TRUE(f->Close());
}

TEST(RecorderRing, AnUncleanStopOfTheLastRunIsAnIncident) {
  const auto dir = test::MakeTempDir("recorder_unclean");
  Ring ring(dir);
  Leftover(dir / "ring", ring.config);
  ASSERT_TRUE(ring.Create()) << ring.error;
  EXPECT_FALSE(std::filesystem::exists(dir / "ring" / "seg-000004"));
  EXPECT_TRUE(std::filesystem::exists(dir / "ring" / "seg-000005"));  // numbering goes on
  std::vector<std::filesystem::path> incidents;
  for (const auto& e : std::filesystem::directory_iterator(dir / "incidents"))
    incidents.push_back(e.path());
  ASSERT_EQ(incidents.size(), 1u);
  EXPECT_NE(incidents[0].filename().string().find("-unclean_stop"), std::string::npos);
  std::ifstream log(incidents[0] / "log.txt");
  std::string line;
  std::getline(log, line);
  EXPECT_EQ(line, "the last words");
}

TEST(RecorderRing, ACleanStopLeavesNoIncident) {
  const auto dir = test::MakeTempDir("recorder_clean");
  Ring ring(dir);
  Leftover(dir / "ring", ring.config);
  std::ofstream(dir / "ring" / kCleanStopMark) << "x";
  ASSERT_TRUE(ring.Create()) << ring.error;
  EXPECT_FALSE(std::filesystem::exists(dir / "ring" / "seg-000004"));
  EXPECT_FALSE(std::filesystem::exists(dir / "ring" / kCleanStopMark));  // this run's is to come
  EXPECT_TRUE(std::filesystem::is_empty(dir / "incidents"));
}

TEST(RecorderRing, AnUnwritableDirectoryIsAClearError) {
  Ring ring("/proc/swlio-blackbox");  // not even root creates folders in /proc
  EXPECT_FALSE(ring.Create());
  EXPECT_NE(ring.error.find("black box: cannot create"), std::string::npos) << ring.error;
}

}  // namespace
}  // namespace swlio::daemon

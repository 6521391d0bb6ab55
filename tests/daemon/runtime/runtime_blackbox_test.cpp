// The black box on a live drive (issue 35): the simulator injects three faults at known times
// (a LiDAR outage at 8 s, an IMU unplug at 20 s, a blind LiDAR at 31 s that makes the estimator
// diverge); exactly those three incidents are kept (besides those of this shared machine's
// load: the estimator falling behind, or the simulator itself seconds late), each around its
// fault with the span asked for, while the ring stays within max_disk_mb. An incident then
// replays byte-identically with swlio-replay --deterministic and follows what the daemon
// estimated live, and swlio-report names the failed subsystem in its summary. A full disk stops
// the ring and nothing else.

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

#include "live_drive.h"
#include "swlio/daemon/blackbox/incident_detector.h"
#include "swlio/daemon/blackbox/ring_segments.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr double kBeforeS = 4.0, kAfterS = 4.0;
constexpr int64_t kMaxDiskMb = 16;

struct Incident {
  std::filesystem::path dir;
  std::string reason;
  int64_t t_event_ns = 0, start_ns = 0, end_ns = 0, asked_start_ns = 0, asked_end_ns = 0;
  std::string yaml;
};

std::string Read(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int64_t Field(const std::string& yaml, const std::string& key) {
  std::smatch m;
  const std::regex re("[{ \\n]" + key + ": (-?[0-9]+)");
  return std::regex_search(yaml, m, re) ? std::stoll(m[1]) : -1;
}

std::vector<Incident> Incidents(const std::filesystem::path& dir) {
  std::vector<Incident> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    Incident i;
    i.dir = e.path();
    i.yaml = Read(i.dir / "incident.yaml");
    std::smatch m;
    if (std::regex_search(i.yaml, m, std::regex("\\nreason: ([a-z_]+)"))) i.reason = m[1];
    i.t_event_ns = Field(i.yaml, "t_event_ns");
    i.start_ns = Field(i.yaml, "start_ns");
    i.end_ns = Field(i.yaml, "end_ns");
    i.asked_start_ns = Field(i.yaml, "asked_start_ns");
    i.asked_end_ns = Field(i.yaml, "asked_end_ns");
    out.push_back(i);
  }
  std::sort(out.begin(), out.end(),
            [](const Incident& a, const Incident& b) { return a.t_event_ns < b.t_event_ns; });
  return out;
}

/// TUM rows: t_ns → position.
std::map<int64_t, Eigen::Vector3d> Tum(const std::filesystem::path& p) {
  std::map<int64_t, Eigen::Vector3d> rows;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double t = 0;
    Eigen::Vector3d x;
    if (s >> t >> x.x() >> x.y() >> x.z()) rows[std::llround(t * 1e9)] = x;
  }
  return rows;
}

int Replay(const std::filesystem::path& incident, const std::filesystem::path& out) {
  const std::string cmd = ::swlio::test::ToolPath("swlio-replay").string() + " '" +
                          incident.string() + "' --deterministic --out '" + out.string() + "' > '" +
                          out.string() + ".log' 2>&1";
  return std::system(cmd.c_str());
}

/// RMS of the replay's positions against the live ones at the same sweeps, after the rigid
/// alignment of one to the other (the replay starts its own world frame); the matched count.
std::pair<double, size_t> AlignedRms(const std::map<int64_t, Eigen::Vector3d>& live,
                                     const std::map<int64_t, Eigen::Vector3d>& replay) {
  std::vector<Eigen::Vector3d> a, b;
  for (const auto& [t, p] : replay) {
    auto it = live.lower_bound(t - 1'000'000);
    if (it != live.end() && std::llabs(it->first - t) <= 1'000'000) {
      a.push_back(p);
      b.push_back(it->second);
    }
  }
  if (a.size() < 3) return {-1.0, a.size()};
  Eigen::Matrix3Xd A(3, static_cast<Eigen::Index>(a.size())), B(3, A.cols());
  for (size_t i = 0; i < a.size(); ++i)
    A.col(static_cast<Eigen::Index>(i)) = a[i], B.col(static_cast<Eigen::Index>(i)) = b[i];
  const Eigen::Matrix4d T = Eigen::umeyama(A, B, false);
  const Eigen::Matrix3Xd moved = (T.topLeftCorner<3, 3>() * A).colwise() + T.topRightCorner<3, 1>();
  return {std::sqrt((moved - B).colwise().squaredNorm().mean()), a.size()};
}

TEST(RuntimeBlackBox, KeepsExactlyTheInjectedFaultsAndReplaysThem) {
  const auto box = ::swlio::test::MakeTempDir("blackbox");
  test::LiveDrive drive;
  drive.duration_s = 42.0;
  drive.speed = 1.0;
  drive.dds_domain = 165;
  drive.faults.lidar_outages = {{8.0, 2.0}};
  drive.faults.serial_unplugs = {{20.0, 2.0}};
  drive.faults.lidar_one_range = {{31.0, 3.0}};
  drive.adjust_config = [&](DaemonConfig* c) {
    c->record.ring = true;
    c->record.directory = box.string();
    c->record.segment_s = 2.0;
    c->record.ring_minutes = 0.5;
    c->record.max_disk_mb = kMaxDiskMb;
    c->record.incident_before_s = kBeforeS;
    c->record.incident_after_s = kAfterS;
    c->window.divergence.max_failed_sweeps = 10;  // 1 s blind: the estimator diverges
  };
  const test::LiveDriveResult r = test::RunLiveDrive(drive);
  ASSERT_TRUE(r.sim_ok) << r.error;
  auto sim_time = [&](int64_t daemon_ns) { return r.SimTime(r.daemon_time.ToHost(daemon_ns)); };

  // The ring never held more than max_disk_mb (health every 100 ms, and at the end).
  uint64_t most = 0;
  for (const test::HealthSample& h : r.health)
    most = std::max(most, h.snapshot.recorder.ring_bytes);
  std::cout << "[ ring ] at most " << static_cast<double>(most) / 1e6 << " MB; "
            << r.final.recorder.segments_deleted << " segments deleted\n";
  EXPECT_LE(most, static_cast<uint64_t>(kMaxDiskMb) * 1'000'000);
  EXPECT_LE(DirectoryBytes(box / "ring"), static_cast<uint64_t>(kMaxDiskMb) * 1'000'000);
  EXPECT_GT(r.final.recorder.segments_deleted, 0u);
  EXPECT_FALSE(r.final.recorder.stopped) << r.final.recorder.error;

  // The injected faults: each one's incident, and when its event may come (simulation s). A
  // simulator that sent late (a starved machine) injected its fault that much later.
  const std::vector<std::string> expected = {"lidar_silent", "imu_silent", "divergence"};
  std::array<std::pair<double, double>, 3> when = {{{8.9, 10.1}, {20.0, 21.6}, {31.5, 35.0}}};
  for (auto& [from_s, to_s] : when) {
    const double late_s = r.stats.WorstLatenessMs(from_s - 2.0, to_s) * 1e-3 * r.speed;
    if (late_s > 0.0)
      std::cout << "[ note ] the simulator sent " << late_s << " s late by " << to_s << " s\n";
    to_s += late_s;
  }
  auto injected = [&](const Incident& i, double t_s) {
    for (size_t k = 0; k < expected.size(); ++k) {
      if (i.reason == expected[k] && t_s >= when[k].first && t_s <= when[k].second) return true;
    }
    return false;
  };
  // Two kinds of incident are this shared machine's load (other tests beside this one), not
  // the daemon's, and one is the drive's end: shown and set aside. An incident after the drive
  // (the simulator closes its pty when it is done, and the daemon says its serial device went
  // away if the test observes once more before it sees the simulator done: an extra
  // imu_silent); an estimator that fell behind; and an incident no fault
  // explains where the simulator itself had sent 200 ms late or more in the 3 s before: its
  // sensors really went silent, or their clocks stepped, for the daemon (seen under
  // `stress-ng --cpu 6`: the simulator seconds late, an extra imu_silent or clock_jump).
  std::vector<Incident> kept;
  std::vector<std::string> reasons;
  for (const Incident& i : Incidents(box / "incidents")) {
    const double t_s = sim_time(i.t_event_ns);
    std::cout << "[ incident ] " << i.dir.filename().string() << " at " << t_s << " s, kept "
              << sim_time(i.start_ns) << " .. " << sim_time(i.end_ns) << " s\n"
              << i.yaml;
    if (i.reason == "estimator_behind") continue;
    if (t_s >= drive.duration_s) {
      std::cout << "[ note ] set aside: " << i.reason << " at " << t_s << " s, after the drive\n";
      continue;
    }
    const double sim_late_ms = r.stats.WorstLatenessMs(t_s - 3.0, t_s);
    if (!injected(i, t_s) && sim_late_ms >= 200.0) {
      std::cout << "[ note ] set aside: " << i.reason << " at " << t_s << " s, the simulator sent "
                << sim_late_ms << " ms late before it\n";
      continue;
    }
    kept.push_back(i);
    reasons.push_back(i.reason);
  }
  ASSERT_EQ(reasons, expected);
  for (size_t i = 0; i < kept.size(); ++i) {
    const Incident& k = kept[i];
    EXPECT_GE(sim_time(k.t_event_ns), when[i].first) << k.reason;
    EXPECT_LE(sim_time(k.t_event_ns), when[i].second) << k.reason;
    EXPECT_EQ(k.asked_start_ns, k.t_event_ns - static_cast<int64_t>(kBeforeS * 1e9));
    EXPECT_EQ(k.asked_end_ns, k.t_event_ns + static_cast<int64_t>(kAfterS * 1e9));
    EXPECT_LE(k.start_ns, k.asked_start_ns) << k.reason;  // whole segments around the span
    EXPECT_GE(k.end_ns, k.asked_end_ns) << k.reason;
    EXPECT_LE(k.end_ns - k.start_ns,
              static_cast<int64_t>((kBeforeS + kAfterS + 2 * 2.0 + 1) * 1e9));
    for (const char* f : {"lidar.pcap", "imu.xbus", "imu.rx.csv", "health.csv", "log.txt",
                          "odometry.tum", "config.yaml", "manifest.yaml"})
      EXPECT_GT(std::filesystem::file_size(k.dir / f), 0u) << k.reason << " " << f;
  }
  EXPECT_NE(Read(kept[0].dir / "log.txt").find("incident: lidar_silent"), std::string::npos);

  // The LiDAR outage's incident, replayed twice: the same bytes, and the live estimate's path.
  const auto out = ::swlio::test::MakeTempDir("blackbox_replay");
  ASSERT_EQ(Replay(kept[0].dir, out / "a.tum"), 0) << Read(out / "a.tum.log");
  ASSERT_EQ(Replay(kept[0].dir, out / "b.tum"), 0) << Read(out / "b.tum.log");
  EXPECT_EQ(Read(out / "a.tum"), Read(out / "b.tum"));
  EXPECT_NE(Read(out / "a.tum.log").find("recorded by this version"), std::string::npos)
      << Read(out / "a.tum.log");
  const auto [rms, matched] = AlignedRms(Tum(kept[0].dir / "odometry.tum"), Tum(out / "a.tum"));
  std::cout << "[ replay ] " << matched << " sweeps matched, aligned RMS " << rms << " m\n";
  EXPECT_GE(matched, 50u);
  EXPECT_GE(rms, 0.0);
  EXPECT_LT(rms, 0.10);
  // swlio-report on the kept incidents: the failed subsystem named in the summary.
  for (const auto& [k, subsystem] :
       {std::pair{&kept[0], "LiDAR"}, std::pair{&kept[2], "estimator"}}) {
    const std::filesystem::path page = out / (k->reason + ".html");
    const std::string cmd = ::swlio::test::ToolPath("swlio-report").string() + " '" +
                            k->dir.string() + "' --no-replay -o '" + page.string() + "' > '" +
                            page.string() + ".log' 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << Read(page.string() + ".log");
    const std::string html = Read(page);
    EXPECT_NE(html.find(std::string("failed</span> <b>") + subsystem + "</b>"), std::string::npos)
        << k->reason << ": " << page;
    EXPECT_NE(html.find(k->reason), std::string::npos);
  }
}

// The black box on a 3 MB tmpfs: the disk fills within seconds, the ring stops and says why in
// health; the daemon goes on tracking and publishing as before, and no pipeline queue drops.
TEST(RuntimeBlackBox, AFullDiskStopsTheRingAndNothingElse) {
  if (geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
  const auto box = ::swlio::test::MakeTempDir("blackbox_full");
  if (mount("tmpfs", box.c_str(), "tmpfs", 0, "size=3m") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
  test::LiveDrive drive;
  drive.duration_s = 12.0;
  drive.dds_domain = 166;
  drive.adjust_config = [&](DaemonConfig* c) {
    c->record.ring = true;
    c->record.directory = box.string();
  };
  const test::LiveDriveResult r = test::RunLiveDrive(drive);
  umount2(box.c_str(), MNT_DETACH);
  ASSERT_TRUE(r.sim_ok) << r.error;
  r.ShowPublished("swlio: black box");
  EXPECT_TRUE(r.final.recorder.stopped);
  EXPECT_NE(r.final.recorder.error.find("No space left on device"), std::string::npos)
      << r.final.recorder.error;
  EXPECT_GT(r.final.recorder.discarded, 0u);
  EXPECT_TRUE(r.PublishedSaid("swlio: black box", "stopped, nothing is recorded"));
  EXPECT_TRUE(r.ready);
  EXPECT_EQ(PipelineDrops(r.final), 0u);
  EXPECT_EQ(r.final.optimizer.reinitializations, 0u);
  EXPECT_EQ(r.final.optimizer.tracking, TrackingState::kTracking);
  EXPECT_GE(r.PosesBetween(6.0, 11.0), 1800u);  // 400 Hz: the pose goes on after the stop
}

}  // namespace
}  // namespace swlio::daemon

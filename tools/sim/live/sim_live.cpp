#include "live/sim_live.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <optional>
#include <vector>

#include "live/serial_backlog.h"
#include "recording/actors_csv.h"
#include "recording/sim_recording.h"
#include "scenarios/sim_laps.h"
#include "swlio/core/time.h"

namespace swlio::sim {
namespace {

int64_t MonotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * kNsPerSec + ts.tv_nsec;
}

void SleepUntil(int64_t t_ns) {
  timespec ts{static_cast<time_t>(t_ns / kNsPerSec), static_cast<long>(t_ns % kNsPerSec)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

struct Endpoints {
  int udp = -1;
  int pty_master = -1;
  int pty_slave = -1;  ///< kept open so the line never hangs up before the reader opens it
  void ClosePty() {
    for (int* fd : {&pty_master, &pty_slave}) {
      if (*fd >= 0) close(*fd);
      *fd = -1;
    }
  }
  ~Endpoints() {
    ClosePty();
    if (udp >= 0) close(udp);
  }
};

/// A new pseudo-terminal in raw mode, behind `options.pty_link` when set.
bool OpenPty(const LiveOptions& options, Endpoints* ep, std::string* error) {
  char name[128] = {};
  if (openpty(&ep->pty_master, &ep->pty_slave, name, nullptr, nullptr) != 0) {
    *error = "cannot open a pseudo-terminal";
    return false;
  }
  termios tio{};
  tcgetattr(ep->pty_slave, &tio);
  cfmakeraw(&tio);  // binary Xbus bytes must pass untouched until the reader sets its mode
  tcsetattr(ep->pty_slave, TCSANOW, &tio);
  fcntl(ep->pty_master, F_SETFL, fcntl(ep->pty_master, F_GETFL) | O_NONBLOCK);
  if (!options.pty_link.empty()) {
    std::filesystem::remove(options.pty_link);
    std::error_code ec;
    std::filesystem::create_symlink(name, options.pty_link, ec);
    if (ec) {
      *error = "cannot create " + options.pty_link + ": " + ec.message();
      return false;
    }
  }
  std::printf("pty: %s\n", name);
  std::fflush(stdout);
  return true;
}

bool OpenEndpoints(const LiveOptions& options, Endpoints* ep, std::string* error) {
  ep->udp = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (ep->udp < 0) {
    *error = "cannot open the UDP socket";
    return false;
  }
  return OpenPty(options, ep, error);
}

/// Serial unplug and replug: the device (and its link) goes away, then a new one appears at
/// the same link, as a USB adapter re-enumerates.
bool FollowPlug(const LiveOptions& options,
                bool unplugged,
                Endpoints* ep,
                FaultCounts* counts,
                std::string* error) {
  const bool plugged = ep->pty_master >= 0;
  if (unplugged && plugged) {
    ep->ClosePty();
    if (!options.pty_link.empty()) std::filesystem::remove(options.pty_link);
    ++counts->unplugs;
  } else if (!unplugged && !plugged) {
    return OpenPty(options, ep, error);
  }
  return true;
}

/// Waits (up to `timeout_s`) until the reader has taken every byte written to the pty: closing
/// the master hangs the line up and would discard what is still queued. The queue must stay
/// empty for 50 ms: bytes still in the pty's flip buffer (pushed to the line discipline by a
/// kernel worker, late under load) are not counted by FIONREAD yet.
void WaitForPtyDrained(int slave_fd, double timeout_s) {
  const int64_t deadline = MonotonicNs() + SecToNs(timeout_s);
  int64_t empty_since = -1;
  int queued = 0;
  while (ioctl(slave_fd, FIONREAD, &queued) == 0 && MonotonicNs() < deadline) {
    if (queued > 0) {
      empty_since = -1;
    } else if (empty_since < 0) {
      empty_since = MonotonicNs();
    } else if (MonotonicNs() - empty_since >= 50 * kNsPerMs) {
      return;
    }
    SleepUntil(MonotonicNs() + kNsPerMs);
  }
}

void SendUdp(int fd, uint16_t port, std::span<const uint8_t> bytes, LiveStats* stats) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // never anywhere else
  const ssize_t n =
      sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  (n == static_cast<ssize_t>(bytes.size()) ? stats->udp_sent : stats->udp_errors)++;
}

/// Sleeps until `t_ns`; meanwhile, bytes waiting for room in the pty go out as it empties.
void SleepWriting(int64_t t_ns, int fd, SerialBacklog* backlog) {
  while (!backlog->empty() && !backlog->held() && fd >= 0) {
    const int64_t left_ns = t_ns - MonotonicNs();
    if (left_ns <= 0) return;
    pollfd p{fd, POLLOUT, 0};
    if (poll(&p, 1, static_cast<int>((left_ns + kNsPerMs - 1) / kNsPerMs)) <= 0) break;
    backlog->Flush(fd, MonotonicNs());
  }
  SleepUntil(t_ns);
}

/// After the last sample: what still waits goes out, for up to `timeout_s`.
void DrainBacklog(int fd, SerialBacklog* backlog, double timeout_s) {
  const int64_t deadline = MonotonicNs() + SecToNs(timeout_s);
  while (!backlog->empty() && fd >= 0 && MonotonicNs() < deadline) {
    SleepWriting(std::min(deadline, MonotonicNs() + 100 * kNsPerMs), fd, backlog);
  }
}

/// How late the sends were against their schedule, for the report.
void SummarizeLateness(std::vector<float>* lateness_ms, LiveStats* stats) {
  if (lateness_ms->empty()) return;
  std::sort(lateness_ms->begin(), lateness_ms->end());
  auto at = [&](double q) {
    return static_cast<double>(
        (*lateness_ms)[static_cast<size_t>(q * static_cast<double>(lateness_ms->size() - 1))]);
  };
  stats->lateness_p50_ms = at(0.5);
  stats->lateness_p99_ms = at(0.99);
  stats->max_lateness_ms = static_cast<double>(lateness_ms->back());
  stats->late_sends = static_cast<uint64_t>(
      lateness_ms->end() - std::upper_bound(lateness_ms->begin(), lateness_ms->end(),
                                            static_cast<float>(LiveStats::kLateMs)));
}

/// Opens or extends LiveStats::late_spans with a send due at simulation time t_s.
void TrackLateSpans(double t_s, double late_ms, bool* in_span, LiveStats* stats) {
  if (late_ms <= LiveStats::kStallMs) {
    *in_span = false;
    return;
  }
  std::vector<LiveStats::LateSpan>& spans = stats->late_spans;
  if (!*in_span) {
    if (spans.size() >= LiveStats::kMaxLateSpans) return;
    spans.push_back({t_s, t_s, late_ms});
    *in_span = true;
  }
  spans.back().to_s = t_s;
  spans.back().worst_ms = std::max(spans.back().worst_ms, late_ms);
}

/// imu_writes.csv: per IMU sample, when it was taken and when its frame went into the pty (host
/// CLOCK_MONOTONIC ns; 0: never written). Pose age from the serial line to a subscriber is
/// measured against it (scripts/live_figures.py).
template <typename HostNs>
void WriteImuWrites(const std::filesystem::path& path,
                    const std::vector<SimImuSample>& imu,
                    HostNs host_ns,
                    const std::vector<int64_t>& written_ns) {
  std::ofstream f(path);
  f << "t_sample_ns,t_written_ns\n";
  for (size_t k = 0; k < imu.size(); ++k) {
    f << host_ns(imu[k].t_true_ns) << ',' << (k < written_ns.size() ? written_ns[k] : 0) << '\n';
  }
}

void Report(const SerialBacklog& backlog, LiveStats* stats) {
  const SerialBacklogStats& b = backlog.stats();
  stats->imu_bytes = b.written;
  stats->imu_bytes_dropped = b.dropped;
  stats->imu_bytes_delayed = b.delayed;
  stats->imu_backlog_max_bytes = b.max_backlog;
  stats->imu_backlog_max_wait_ms = static_cast<double>(b.max_wait_ns) * 1e-6;
}

}  // namespace

double LiveStats::WorstLatenessMs(double from_s, double to_s) const {
  double worst = 0.0;
  for (const LateSpan& span : late_spans) {
    if (span.to_s >= from_s && span.from_s <= to_s) worst = std::max(worst, span.worst_ms);
  }
  return worst;
}

bool RunLive(const SimSetup& setup,
             const LiveOptions& options,
             const volatile bool* stop,
             LiveStats* stats,
             std::string* error) {
  Endpoints ep;
  if (!OpenEndpoints(options, &ep, error)) return false;
  if (!options.out_dir.empty()) {
    // The rig (extrinsic, ports, sensor models) before streaming, so that whoever starts the
    // receiver can configure it; counts are zero until the final manifest replaces it.
    std::filesystem::create_directories(options.out_dir);
    std::ofstream(options.out_dir / "manifest.yaml") << ManifestYaml(
        setup, RecordingStats{}, MonotonicNs() + SecToNs(options.start_delay_s), "live");
  }
  const std::vector<SimImuSample> imu = SimulateImu(*setup.trajectory, setup.imu, setup.seed);
  const std::vector<SimGnssFix> fixes =
      SimulateGnss(*setup.trajectory, setup.gnss, imu, setup.seed);
  size_t next_fix = 0;
  // A repeated route (RepeatRoute) casts its first lap before streaming and replays it.
  std::optional<LidarLaps> laps;
  std::optional<LidarSimulator> once;
  // A single lap (LidarLaps of a route that is not repeated) is the whole drive.
  const bool repeated = setup.trajectory->lap_period_s() > 0.0;
  if (repeated || options.precast) {
    std::fprintf(stderr, "sim: casting the %s (%.0f s of driving) before streaming\n",
                 repeated ? "first lap" : "whole drive",
                 repeated ? setup.trajectory->lap_period_s() : setup.trajectory->duration_s());
    laps.emplace(setup);
  } else {
    once.emplace(setup.world.get(), setup.trajectory.get(), setup.lidar, setup.seed);
  }
  auto next_packet = [&](SimPacket* p) { return laps ? laps->Next(p) : once->Next(p); };
  // The delay after the preparation above, so that a receiver started now is in time.
  std::fprintf(stderr, "sim: streaming in %.1f s\n", options.start_delay_s);
  if (options.start_delay_s > 0.0) SleepUntil(MonotonicNs() + SecToNs(options.start_delay_s));
  const int64_t start_ns = MonotonicNs();
  stats->start_ns = start_ns;
  if (options.on_start) options.on_start(start_ns);
  auto host_ns = [&](int64_t sim_ns) {
    return start_ns + static_cast<int64_t>(static_cast<double>(sim_ns) / options.speed);
  };
  FaultInjector faults(options.faults);
  SimPacket packet;
  bool have_packet = next_packet(&packet);
  size_t i = 0;
  std::vector<uint8_t> burst;
  std::array<uint8_t, 512> frame{};
  SerialBacklog backlog;
  std::vector<int64_t> written_ns;
  backlog.ReportWritesTo(options.imu_write_ns != nullptr ? options.imu_write_ns : &written_ns);
  std::vector<float> lateness_ms;
  lateness_ms.reserve(imu.size() + 1024);
  bool in_late_span = false;
  while (!*stop && (have_packet || i < imu.size())) {
    const bool lidar_first = have_packet && (i >= imu.size() || packet.t_rx_ns <= imu[i].t_rx_ns);
    const int64_t due = host_ns(lidar_first ? packet.t_rx_ns : imu[i].t_rx_ns);
    SleepWriting(due, ep.pty_master, &backlog);
    const double late_ms = static_cast<double>(MonotonicNs() - due) * 1e-6;
    lateness_ms.push_back(static_cast<float>(late_ms));
    const double t_s = NsToSec(lidar_first ? packet.t_rx_ns : imu[i].t_rx_ns);
    TrackLateSpans(t_s, late_ms, &in_late_span, stats);
    if (!FollowPlug(options, faults.Unplugged(t_s), &ep, faults.mutable_counts(), error)) {
      return false;
    }
    if (ep.pty_master < 0) backlog.Clear();  // unplugged: the adapter's buffer went with it
    backlog.Hold(faults.SerialStalled(t_s));
    if (lidar_first) {
      const bool difop = packet.dst_port != setup.lidar.msop_port;
      if (faults.PassDatagram(t_s, difop, packet.bytes)) {
        SendUdp(ep.udp, difop ? options.difop_port : options.msop_port, packet.bytes, stats);
      }
      have_packet = next_packet(&packet);
      continue;
    }
    burst.clear();
    faults.AppendGarbage(t_s, &burst);
    const size_t first = i;
    for (const int64_t t = imu[i].t_rx_ns; i < imu.size() && imu[i].t_rx_ns == t; ++i) {
      SimImuSample sample = imu[i];
      if (!faults.PassImu(t_s, &sample)) continue;
      const size_t n = EncodeImuFrame(sample, frame, PvtForSample(fixes, i, &next_fix));
      burst.insert(burst.end(), frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(n));
    }
    if (ep.pty_master >= 0) backlog.Send(ep.pty_master, burst, first, i, MonotonicNs());
  }
  backlog.Hold(false);  // a stall that outlasts the drive ends with it
  DrainBacklog(ep.pty_master, &backlog, 30.0);
  Report(backlog, stats);
  SummarizeLateness(&lateness_ms, stats);
  stats->faults = faults.counts();
  if (ep.pty_slave >= 0) WaitForPtyDrained(ep.pty_slave, 2.0);
  if (!options.out_dir.empty()) {
    std::filesystem::create_directories(options.out_dir);
    std::ofstream gt(options.out_dir / "groundtruth.tum");
    gt << "# timestamp tx ty tz qx qy qz qw  (IMU body frame, host CLOCK_MONOTONIC s)\n";
    for (int64_t k = 0; static_cast<double>(k) / setup.gt_rate_hz <= SimDuration(setup); ++k) {
      const double t = static_cast<double>(k) / setup.gt_rate_hz;
      gt << TumLine(setup, t, start_ns + SecToNs(t / options.speed)) << '\n';
    }
    if (setup.world->actors) {
      std::ofstream actors(options.out_dir / "actors.csv");
      WriteActorsCsv(
          *setup.world->actors, SimDuration(setup),
          [&](double t_s) { return start_ns + SecToNs(t_s / options.speed); }, actors,
          setup.trajectory->lap_period_s());
    }
    WriteImuWrites(options.out_dir / "imu_writes.csv", imu, host_ns,
                   options.imu_write_ns != nullptr ? *options.imu_write_ns : written_ns);
    RecordingStats rs;
    rs.msop_packets = laps ? laps->msop_packets() : once->msop_packets();
    rs.difop_packets = laps ? laps->difop_packets() : once->difop_packets();
    rs.imu_frames = imu.size();
    rs.gnss_items = fixes.size();
    std::ofstream(options.out_dir / "manifest.yaml") << ManifestYaml(setup, rs, start_ns, "live");
  }
  return true;
}

}  // namespace swlio::sim

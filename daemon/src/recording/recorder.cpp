#include "swlio/daemon/recording/recorder.h"

#include <Eigen/Geometry>
#include <cstdlib>
#include <initializer_list>
#include <string>

#include "swlio/core/exact_number.h"
#include "swlio/drivers/candump_log.h"
#include "swlio/drivers/recording_format.h"

namespace swlio::daemon {
namespace {

std::string List(std::initializer_list<double> values) {
  std::string s = "[";
  for (const double v : values) s += (s.size() > 1 ? ", " : "") + ExactNumber(v);
  return s + "]";
}

/// Every number exactly (shortest round trip): swlio-run, swlio-replay and scripts read them.
void WriteManifest(const std::filesystem::path& path,
                   const DaemonConfig& config,
                   const Eigen::Isometry3d& T_imu_lidar,
                   const TimeScale& time,
                   const ClockOffsetSample& offset) {
  const Eigen::Vector3d t = T_imu_lidar.translation();
  const Eigen::Quaterniond q(T_imu_lidar.linear());
  std::ofstream y(path);
  y << "# swliod recording: raw sensor bytes with host receive times (CLOCK_MONOTONIC ns)\n"
    << "# format_version 2: extrinsic_T_imu_lidar in the LiDAR vendor driver's frame (x forward,\n"
    << "# y left, z up); version 1 (before swlio issue 32) used the RoboSense manual's frame.\n"
    << "format_version: " << drivers::kRecordingFormatVersion << "\nmode: daemon\n"
    << "# Receive times are on the daemon's time base (time_scale.h): host = origin + (t −\n"
    << "# origin) / scale. Both are 1 / any on a robot (times are host times).\n"
    << "time_scale: " << ExactNumber(time.scale) << "\ntime_origin_ns: " << time.origin_ns << "\n"
    << "# The published stamps' clock (ipc.stamp_clock), and CLOCK_REALTIME − CLOCK_MONOTONIC at\n"
    << "# the start; clock_offsets.csv has it at every change (host times, before time_scale).\n"
    << "stamp_clock: " << config.ipc.stamp_clock
    << "\nrealtime_minus_monotonic_ns: " << offset.offset_ns << "\n"
    << "extrinsic_T_imu_lidar:  # LiDAR points (x forward, y left, z up) into the IMU frame\n"
    << "  translation_m: " << List({t.x(), t.y(), t.z()}) << "\n"
    << "  quaternion_xyzw: " << List({q.x(), q.y(), q.z(), q.w()}) << "\n"
    << "lidar:\n  model: " << config.lidar.model << "\n  msop_port: " << config.lidar.msop_port
    << "\n  difop_port: " << config.lidar.difop_port
    << "\n  lens_offset_m: " << ExactNumber(config.lidar.EffectiveLensOffsetM())
    << "\nimu:\n  device: " << config.imu.device << "\n  baud: " << config.imu.baud
    << "\nfiles: {lidar: lidar.pcap, imu: imu.xbus, imu_rx: imu.rx.csv, clock_offsets: "
       "clock_offsets.csv}\n";
}

}  // namespace

Recorder::Recorder(const DaemonConfig& config, const TimeScale& time)
    : time_(time), msop_port_(config.lidar.msop_port), difop_port_(config.lidar.difop_port) {}

Recorder::~Recorder() = default;

std::unique_ptr<Recorder> Recorder::Create(const std::filesystem::path& dir,
                                           const DaemonConfig& config,
                                           const Eigen::Isometry3d& T_imu_lidar,
                                           const TimeScale& time,
                                           std::string* error,
                                           const StampClock* stamps) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create " + dir.string() + ": " + ec.message();
    return nullptr;
  }
  std::unique_ptr<Recorder> r(new Recorder(config, time));
  r->pcap_ = drivers::PcapWriter::Create((dir / "lidar.pcap").string(), {}, error);
  if (!r->pcap_) return nullptr;
  r->xbus_.open(dir / "imu.xbus", std::ios::binary);
  r->rx_csv_.open(dir / "imu.rx.csv");
  if (!r->xbus_ || !r->rx_csv_) {
    *error = "cannot write imu.xbus / imu.rx.csv in " + dir.string();
    return nullptr;
  }
  r->rx_csv_ << "byte_offset,bytes,t_rx_ns\n";
  r->offsets_csv_.open(dir / "clock_offsets.csv");
  if (!r->offsets_csv_) {
    *error = "cannot write clock_offsets.csv in " + dir.string();
    return nullptr;
  }
  r->offsets_csv_ << "t_monotonic_ns,realtime_minus_monotonic_ns\n";
  if (stamps != nullptr) r->clocks_ = stamps->clocks();
  if (config.can.enabled) {
    r->can_interface_ = config.can.interface;
    r->can_log_.open(dir / "can.log");
    if (!r->can_log_) {
      *error = "cannot write can.log in " + dir.string();
      return nullptr;
    }
  }
  const ClockOffsetSample start = SampleClockOffset(r->clocks_);
  WriteManifest(dir / "manifest.yaml", config, T_imu_lidar, time, start);
  r->WriteClockOffset(start);
  return r;
}

void Recorder::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  int64_t next_flush_ns = MonotonicNowNs() + 1'000'000'000;
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    LidarPacket p;
    if (!Drain() && lidar_.WaitPop(&p, 50'000)) WritePacket(p);  // sleep until data arrives
    const int64_t now = MonotonicNowNs();
    RecordClockOffset(now);
    if (now >= next_flush_ns) {
      Flush();
      next_flush_ns = now + 1'000'000'000;
    }
  }
  while (Drain()) {
  }
  next_offset_check_ns_ = 0;  // the offset as the recording ends
  RecordClockOffset(MonotonicNowNs());
  Flush();
}

void Recorder::WritePacket(const LidarPacket& p) {
  const uint16_t port = p.difop ? difop_port_ : msop_port_;
  const bool ok =
      pcap_->Write(time_.ToDaemon(p.t_rx_ns), port, port, std::span(p.bytes).first(p.size));
  (ok ? lidar_packets_ : write_errors_).fetch_add(1, std::memory_order_relaxed);
}

bool Recorder::Drain() {
  bool any = false;
  LidarPacket p;
  while (lidar_.Pop(&p)) {
    WritePacket(p);
    any = true;
  }
  drivers::CanRxFrame f;
  while (can_.Pop(&f)) {
    const bool ok = drivers::WriteCandumpLine(
        can_log_, drivers::MakeCandumpRecord(time_.ToDaemon(f.t_ns), can_interface_, f.frame));
    if (!ok) write_errors_.fetch_add(1, std::memory_order_relaxed);
    any = true;
  }
  SerialChunk c;
  while (serial_.Pop(&c)) {
    xbus_.write(reinterpret_cast<const char*>(c.bytes.data()), c.size);
    rx_csv_ << offset_ << ',' << c.size << ',' << time_.ToDaemon(c.t_rx_ns) << '\n';
    offset_ += c.size;
    serial_bytes_.fetch_add(c.size, std::memory_order_relaxed);
    any = true;
  }
  return any;
}

void Recorder::RecordClockOffset(int64_t now_ns) {
  if (now_ns < next_offset_check_ns_) return;
  next_offset_check_ns_ = now_ns + 10'000'000;
  const ClockOffsetSample s = SampleClockOffset(clocks_);
  if (std::llabs(s.offset_ns - last_offset_row_ns_) > kClockOffsetRowNs) WriteClockOffset(s);
}

void Recorder::WriteClockOffset(const ClockOffsetSample& s) {
  offsets_csv_ << s.t_monotonic_ns << ',' << s.offset_ns << '\n';
  last_offset_row_ns_ = s.offset_ns;
}

void Recorder::Flush() {
  bool ok = pcap_->Flush() && xbus_.flush().good() && rx_csv_.flush().good() &&
            offsets_csv_.flush().good();
  if (can_log_.is_open()) ok = can_log_.flush().good() && ok;
  if (!ok) write_errors_.fetch_add(1, std::memory_order_relaxed);
}

RecorderCounters Recorder::counters() const {
  RecorderCounters c;
  c.lidar_packets = lidar_packets_.load(std::memory_order_relaxed);
  c.serial_bytes = serial_bytes_.load(std::memory_order_relaxed);
  c.write_errors = write_errors_.load(std::memory_order_relaxed);
  return c;
}

}  // namespace swlio::daemon

#include "swlio/daemon/recording/recording_files.h"

#include <cerrno>
#include <cstring>
#include <initializer_list>

#include "swlio/core/exact_number.h"
#include "swlio/daemon/blackbox/health_row.h"
#include "swlio/daemon/output/tum_output.h"
#include "swlio/drivers/candump_log.h"
#include "swlio/drivers/recording_format.h"

namespace swlio::daemon {
namespace {

/// A pcap record: its 16-byte header, then Ethernet (14), IPv4 (20) and UDP (8) headers.
constexpr uint64_t kPcapRecordOverhead = 16 + 14 + 20 + 8;

std::string List(std::initializer_list<double> values) {
  std::string s = "[";
  for (const double v : values) s += (s.size() > 1 ? ", " : "") + ExactNumber(v);
  return s + "]";
}

/// Every number exactly (shortest round trip): swlio-run, swlio-replay and scripts read them.
void WriteManifest(std::ostream& y, const RecordingSetup& setup, const ClockOffsetSample& offset) {
  const DaemonConfig& config = *setup.config;
  const Eigen::Vector3d t = setup.T_imu_lidar.translation();
  const Eigen::Quaterniond q(setup.T_imu_lidar.linear());
  y << "# swliod recording: raw sensor bytes with host receive times (CLOCK_MONOTONIC ns)\n"
    << "# format_version 2: extrinsic_T_imu_lidar in the LiDAR vendor driver's frame (x forward,\n"
    << "# y left, z up); version 1 (before swlio issue 32) used the RoboSense manual's frame.\n"
    << "format_version: " << drivers::kRecordingFormatVersion << "\nmode: daemon\n"
    << "swlio_version: \"" << setup.version << "\"\n"
    << "# Receive times are on the daemon's time base (time_scale.h): host = origin + (t −\n"
    << "# origin) / scale. Both are 1 / any on a robot (times are host times).\n"
    << "time_scale: " << ExactNumber(setup.time.scale)
    << "\ntime_origin_ns: " << setup.time.origin_ns << "\n"
    << "# The published stamps' clock (ipc.stamp_clock), and CLOCK_REALTIME − CLOCK_MONOTONIC at\n"
    << "# the start; clock_offsets.csv has it at every change (host times, before time_scale).\n"
    << "stamp_clock: " << config.ipc.stamp_clock
    << "\nrealtime_minus_monotonic_ns: " << offset.offset_ns << "\n"
    << "extrinsic_T_imu_lidar:  # LiDAR points (x forward, y left, z up) into the IMU frame\n"
    << "  translation_m: " << List({t.x(), t.y(), t.z()}) << "\n"
    << "  quaternion_xyzw: " << List({q.x(), q.y(), q.z(), q.w()}) << "\n"
    << "lidar:\n  model: " << config.lidar.model << "\n  msop_port: " << setup.msop_port
    << "\n  difop_port: " << setup.difop_port
    << "\n  lens_offset_m: " << ExactNumber(config.lidar.EffectiveLensOffsetM())
    << "\nimu:\n  device: " << config.imu.device << "\n  baud: " << config.imu.baud
    << "\nfiles: {lidar: lidar.pcap, imu: imu.xbus, imu_rx: imu.rx.csv, clock_offsets: "
       "clock_offsets.csv, health: health.csv, log: log.txt, odometry: odometry.tum, config: "
       "config.yaml}\n";
}

}  // namespace

RecordingFiles::~RecordingFiles() = default;

std::unique_ptr<RecordingFiles> RecordingFiles::Open(const std::filesystem::path& dir,
                                                     const RecordingSetup& setup,
                                                     const ClockOffsetSample& start,
                                                     std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create " + dir.string() + ": " + ec.message();
    return nullptr;
  }
  std::unique_ptr<RecordingFiles> f(new RecordingFiles());
  f->dir_ = dir;
  f->msop_port_ = setup.msop_port;
  f->difop_port_ = setup.difop_port;
  f->pcap_ = drivers::PcapWriter::Create((dir / "lidar.pcap").string(), {}, error);
  if (!f->pcap_) return nullptr;
  f->xbus_.open(dir / "imu.xbus", std::ios::binary);
  f->rx_csv_.open(dir / "imu.rx.csv");
  f->offsets_csv_.open(dir / "clock_offsets.csv");
  f->health_csv_.open(dir / "health.csv");
  f->log_txt_.open(dir / "log.txt");
  f->odometry_.open(dir / "odometry.tum");
  if (setup.config->can.enabled) {
    f->can_interface_ = setup.config->can.interface;
    f->can_log_.open(dir / "can.log");
  }
  std::ofstream manifest(dir / "manifest.yaml");
  WriteManifest(manifest, setup, start);
  std::ofstream config_yaml(dir / "config.yaml");
  config_yaml << setup.config_text;
  f->rx_csv_ << "byte_offset,bytes,t_rx_ns\n";
  f->offsets_csv_ << "t_monotonic_ns,realtime_minus_monotonic_ns\n";
  f->health_csv_ << kHealthCsvHeader << '\n';
  f->ClockOffset(start);
  if (!f->Check(manifest, "manifest.yaml") || !f->Check(config_yaml, "config.yaml") ||
      !f->Flush()) {
    *error = f->error_;
    return nullptr;
  }
  return f;
}

void RecordingFiles::Fail(const std::string& what) {
  if (!error_.empty()) return;
  const int e = errno;
  error_ = "cannot write " + what + " in " + dir_.string() +
           (e != 0 ? ": " + std::string(std::strerror(e)) : "");
}

bool RecordingFiles::Check(std::ofstream& out, const char* name) {
  if (!out.is_open() || !out.good()) Fail(name);
  return error_.empty();
}

void RecordingFiles::Packet(int64_t t_ns, bool difop, std::span<const uint8_t> payload) {
  if (failed()) return;
  const uint16_t port = difop ? difop_port_ : msop_port_;
  errno = 0;
  if (!pcap_->Write(t_ns, port, port, payload)) return Fail("lidar.pcap");
  bytes_ += kPcapRecordOverhead + payload.size();
  ++lidar_packets_;
}

void RecordingFiles::Serial(int64_t t_ns, std::span<const uint8_t> bytes) {
  if (failed()) return;
  xbus_.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  rx_csv_ << serial_offset_ << ',' << bytes.size() << ',' << t_ns << '\n';
  serial_offset_ += bytes.size();
  bytes_ += bytes.size() + 40;  // and its imu.rx.csv row
  if (Check(xbus_, "imu.xbus")) Check(rx_csv_, "imu.rx.csv");
}

void RecordingFiles::Can(int64_t t_ns, const drivers::CanRxFrame& frame) {
  if (failed() || !can_log_.is_open()) return;
  if (!drivers::WriteCandumpLine(can_log_,
                                 drivers::MakeCandumpRecord(t_ns, can_interface_, frame.frame)))
    return Fail("can.log");
  bytes_ += 48;
}

void RecordingFiles::ClockOffset(const ClockOffsetSample& s) {
  if (failed()) return;
  offsets_csv_ << s.t_monotonic_ns << ',' << s.offset_ns << '\n';
  bytes_ += 40;
  Check(offsets_csv_, "clock_offsets.csv");
}

void RecordingFiles::HealthRow(const std::string& row) {
  if (failed()) return;
  health_csv_ << row << '\n';
  bytes_ += row.size() + 1;
  Check(health_csv_, "health.csv");
}

void RecordingFiles::LogLine(const std::string& line) {
  if (failed()) return;
  log_txt_ << line << '\n';
  bytes_ += line.size() + 1;
  Check(log_txt_, "log.txt");
}

void RecordingFiles::Odometry(const State& state) {
  if (failed()) return;
  WriteTumLine(odometry_, state);
  bytes_ += 100;
  Check(odometry_, "odometry.tum");
}

bool RecordingFiles::Flush() {
  if (failed() || !pcap_) return false;
  errno = 0;
  if (!pcap_->Flush()) Fail("lidar.pcap");
  for (auto [out, name] :
       {std::pair{&xbus_, "imu.xbus"}, std::pair{&rx_csv_, "imu.rx.csv"},
        std::pair{&offsets_csv_, "clock_offsets.csv"}, std::pair{&health_csv_, "health.csv"},
        std::pair{&log_txt_, "log.txt"}, std::pair{&odometry_, "odometry.tum"},
        std::pair{&can_log_, "can.log"}}) {
    if (out->is_open() && !out->flush().good()) Fail(name);
  }
  return !failed();
}

bool RecordingFiles::Close() {
  const bool ok = Flush();
  pcap_.reset();
  for (std::ofstream* out :
       {&xbus_, &rx_csv_, &offsets_csv_, &health_csv_, &log_txt_, &odometry_, &can_log_}) {
    if (out->is_open()) out->close();
  }
  return ok;
}

}  // namespace swlio::daemon

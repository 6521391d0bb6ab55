#include "swlio/daemon/recording_reader.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "swlio/daemon/imu_stage.h"
#include "swlio/daemon/lidar_stage.h"
#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::daemon {

namespace xs = drivers::xsens;

/// The LiDAR side: pcap → LidarStage (decoder, clock model, scan assembler).
struct RecordingReader::Lidar {
  std::unique_ptr<drivers::PcapReader> pcap;
  LidarStage stage;
  HostSweep sweep;
  bool flushed = false;

  explicit Lidar(const drivers::LidarConfig& config) : stage(config) {}

  /// Feeds packets until a sweep is complete; false when the file is exhausted.
  bool NextSweep() {
    drivers::UdpDatagram d;
    while (!stage.Pop(&sweep)) {
      if (!pcap->Next(&d)) {
        if (flushed) return false;
        flushed = true;
        stage.Flush();
        continue;
      }
      stage.Add(d.payload, d.t_ns);
    }
    return true;
  }
};

RecordingReader::~RecordingReader() = default;

std::unique_ptr<RecordingReader> RecordingReader::Open(const std::filesystem::path& dir,
                                                       const drivers::LidarConfig& lidar,
                                                       const drivers::ImuConfig& imu,
                                                       std::string* error) {
  std::unique_ptr<RecordingReader> reader(new RecordingReader());
  if (!reader->ReadImu(dir, imu, error)) return nullptr;
  reader->lidar_ = std::make_unique<Lidar>(lidar);
  drivers::PcapUdpFilter filter;
  filter.dst_ports = {lidar.msop_port, lidar.difop_port};
  reader->lidar_->pcap = drivers::PcapReader::Open((dir / "lidar.pcap").string(), filter, error);
  if (!reader->lidar_->pcap) return nullptr;
  return reader;
}

bool RecordingReader::ReadImu(const std::filesystem::path& dir,
                              const drivers::ImuConfig& imu,
                              std::string* error) {
  std::ifstream bytes(dir / "imu.xbus", std::ios::binary);
  std::ifstream rx(dir / "imu.rx.csv");
  if (!bytes || !rx) {
    *error = "cannot read imu.xbus / imu.rx.csv in " + dir.string();
    return false;
  }
  std::string line;
  std::getline(rx, line);  // header
  ImuStage stage(imu.baud);
  xs::XbusFramer framer;
  xs::XbusFrame frame;
  std::vector<char> chunk;
  while (std::getline(rx, line)) {
    uint64_t offset = 0, size = 0;
    int64_t t_rx = 0;
    char c1 = 0, c2 = 0;
    std::istringstream ls(line);
    if (!(ls >> offset >> c1 >> size >> c2 >> t_rx) || c1 != ',' || c2 != ',') continue;
    chunk.resize(size);
    bytes.read(chunk.data(), static_cast<std::streamsize>(size));
    auto data = std::span(reinterpret_cast<const uint8_t*>(chunk.data()),
                          static_cast<size_t>(bytes.gcount()));
    while (!data.empty()) {
      const size_t taken = framer.Feed(data);
      data = data.subspan(taken);
      while (framer.Next(&frame)) {
        xs::MtData2Sample m;
        if (frame.mid != xs::mid::kMtData2 ||
            xs::DecodeMtData2(frame.payload, &m) != xs::MtData2Status::kOk) {
          continue;
        }
        if (auto s = stage.Map(ToImuRaw(m, t_rx, frame.frame_bytes))) imu_.push_back(*s);
      }
    }
  }
  stats_.imu_samples = imu_.size();
  stats_.imu_checksum_errors = framer.stats().checksum_errors;
  stats_.imu_skipped_bytes = framer.stats().skipped_bytes;
  stats_.imu_clock = stage.clock();
  return true;
}

bool RecordingReader::Next(RecordingEvent* event) {
  if (!have_scan_) {
    if (lidar_->NextSweep()) {
      pending_scan_ = std::move(lidar_->sweep.scan);
      have_scan_ = true;
      const LidarStageCounters& c = lidar_->stage.counters();
      stats_.lidar_packets = c.data_packets;
      stats_.scans = c.sweeps;
      stats_.partial_scans = c.partial_sweeps;
      stats_.missing_packets = c.missing_packets;
      stats_.lidar_clock = lidar_->stage.clock();
    }
  }
  if (imu_next_ < imu_.size() && (!have_scan_ || imu_[imu_next_].t_ns <= pending_scan_.t_end_ns)) {
    event->kind = RecordingEvent::Kind::kImu;
    event->imu = imu_[imu_next_++];
    return true;
  }
  if (!have_scan_) return false;
  event->kind = RecordingEvent::Kind::kScan;
  event->scan = std::move(pending_scan_);
  have_scan_ = false;
  return true;
}

TimeScale ManifestTimeScale(const std::filesystem::path& dir) {
  std::ifstream in(dir / "manifest.yaml");
  std::string line;
  TimeScale t;
  double scale = 0.0;
  long long origin = 0;
  while (std::getline(in, line)) {
    if (std::sscanf(line.c_str(), "time_scale: %lf", &scale) == 1 && scale > 0.0) t.scale = scale;
    if (std::sscanf(line.c_str(), "time_origin_ns: %lld", &origin) == 1) t.origin_ns = origin;
  }
  return t;
}

drivers::LidarConfig WithManifestPorts(const std::filesystem::path& dir,
                                       drivers::LidarConfig lidar) {
  std::ifstream in(dir / "manifest.yaml");
  std::string line;
  unsigned port = 0;
  while (std::getline(in, line)) {
    if (std::sscanf(line.c_str(), " msop_port: %u", &port) == 1 && port <= 65535)
      lidar.msop_port = static_cast<uint16_t>(port);
    if (std::sscanf(line.c_str(), " difop_port: %u", &port) == 1 && port <= 65535)
      lidar.difop_port = static_cast<uint16_t>(port);
  }
  return lidar;
}

std::optional<Eigen::Isometry3d> ManifestExtrinsic(const std::filesystem::path& dir) {
  std::ifstream in(dir / "manifest.yaml");
  std::string line;
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1};
  int found = 0;
  while (std::getline(in, line)) {
    found += std::sscanf(line.c_str(), " translation_m: [%lf, %lf, %lf]", &t[0], &t[1], &t[2]) == 3;
    found += std::sscanf(line.c_str(), " quaternion_xyzw: [%lf, %lf, %lf, %lf]", &q[0], &q[1],
                         &q[2], &q[3]) == 4;
  }
  if (found != 2) return std::nullopt;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  return T;
}

}  // namespace swlio::daemon

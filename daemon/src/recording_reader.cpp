#include "swlio/daemon/recording_reader.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/scan_assembler.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::daemon {

namespace xs = drivers::xsens;

/// The LiDAR side: pcap → RS16 decoder → clock model → scan assembler.
struct RecordingReader::Lidar {
  std::unique_ptr<drivers::PcapReader> pcap;
  drivers::Rs16Decoder decoder;
  drivers::ScanAssembler assembler;
  drivers::ClockModel clock;
  drivers::LidarPacketDecoder::ReturnBuffer buffer{};
  bool flushed = false;

  Lidar(const drivers::LidarConfig& config, drivers::ClockModelConfig clock_config)
      : decoder(config), assembler(AssemblerConfig(config)), clock(clock_config) {}

  static drivers::ScanAssemblerConfig AssemblerConfig(const drivers::LidarConfig& config) {
    drivers::ScanAssemblerConfig c;
    c.cut_angle_deg = config.cut_angle_deg;
    return c;
  }

  /// Feeds packets until a scan is complete; false when the file is exhausted.
  bool NextScan(drivers::AssembledScan* out, RecordingStats* stats) {
    drivers::UdpDatagram d;
    while (!assembler.PopScan(out)) {
      if (!pcap->Next(&d)) {
        if (flushed) return false;
        flushed = true;
        assembler.Flush();
        continue;
      }
      const auto kind = decoder.Classify(d.payload);
      if (kind == drivers::LidarPacketKind::kInfo) {
        decoder.DecodeInfo(d.payload);
        assembler.SetNominal(decoder.PacketsPerRevolution(),
                             decoder.Rpm() > 0 ? static_cast<int64_t>(60e9 / decoder.Rpm()) : 0);
        continue;
      }
      drivers::LidarPacketSummary summary;
      if (kind != drivers::LidarPacketKind::kData ||
          decoder.DecodeData(d.payload, buffer, &summary) != drivers::DecodeStatus::kOk) {
        continue;
      }
      ++stats->lidar_packets;
      clock.Observe(summary.t_sensor_ns, d.t_ns);
      assembler.AddPacket(std::span(buffer).first(summary.returns), summary, d.t_ns);
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
  drivers::ClockModelConfig clock;
  // RS16 header time is the packet's first firing; it arrives after 24 firing sequences.
  clock.fixed_latency_ns = 23 * 55'500 + 15 * 2'800;
  reader->lidar_ = std::make_unique<Lidar>(lidar, clock);
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
  drivers::ClockModelConfig clock_config;
  clock_config.wrap_period_ns = xs::SampleTimeFineToNs(0xFFFFFFFFu) + 100'000;
  drivers::ClockModel clock(clock_config);
  xs::XbusFramer framer;
  xs::XbusFrame frame;
  std::vector<char> chunk;
  bool latency_set = false;
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
            xs::DecodeMtData2(frame.payload, &m) != xs::MtData2Status::kOk || !m.sample_time_fine) {
          continue;
        }
        if (!latency_set) {  // 10 bits per byte on an 8N1 line
          clock_config.fixed_latency_ns = static_cast<int64_t>(
              static_cast<double>(frame.frame_bytes) * 10.0 / static_cast<double>(imu.baud) * 1e9);
          clock = drivers::ClockModel(clock_config);
          latency_set = true;
        }
        const int64_t stf = xs::SampleTimeFineToNs(*m.sample_time_fine);
        const int64_t host = clock.Observe(stf, t_rx);
        if (auto s = xs::ToImuSample(m, host)) imu_.push_back(*s);
      }
    }
  }
  stats_.imu_samples = imu_.size();
  stats_.imu_checksum_errors = framer.stats().checksum_errors;
  stats_.imu_skipped_bytes = framer.stats().skipped_bytes;
  stats_.imu_clock = clock.stats();
  return true;
}

bool RecordingReader::Next(RecordingEvent* event) {
  if (!have_scan_) {
    drivers::AssembledScan assembled;
    if (lidar_->NextScan(&assembled, &stats_)) {
      pending_scan_ = std::move(assembled.scan);
      pending_scan_.t_start_ns = lidar_->clock.ToHost(pending_scan_.t_start_ns);
      pending_scan_.t_end_ns = lidar_->clock.ToHost(pending_scan_.t_end_ns);
      have_scan_ = true;
      ++stats_.scans;
      stats_.partial_scans += pending_scan_.partial ? 1 : 0;
      stats_.missing_packets += assembled.missing_packets;
      stats_.lidar_clock = lidar_->clock.stats();
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

#include "swlio/daemon/recording/recording_reader.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "swlio/daemon/sensors/imu_stage.h"
#include "swlio/daemon/sensors/lidar_stage.h"
#include "swlio/drivers/candump_log.h"
#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/wheel_odom_decoder.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::daemon {

namespace xs = drivers::xsens;

namespace {

/// `a` comes first when not after `b` (an absent time never does).
bool NotAfter(const int64_t* a, const int64_t* b) {
  return a != nullptr && (b == nullptr || *a <= *b);
}

}  // namespace

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
  return Open(dir, lidar, imu, RecordingReadOptions{}, error);
}

std::unique_ptr<RecordingReader> RecordingReader::Open(const std::filesystem::path& dir,
                                                       const drivers::LidarConfig& lidar,
                                                       const drivers::ImuConfig& imu,
                                                       const RecordingReadOptions& options,
                                                       std::string* error) {
  if (std::string problem = ManifestVersionProblem(dir); !problem.empty()) {
    *error = std::move(problem);
    return nullptr;
  }
  std::unique_ptr<RecordingReader> reader(new RecordingReader());
  if (!reader->ReadImu(dir, imu, options.gnss, error)) return nullptr;
  if (options.wheel && !reader->ReadWheel(dir, *options.wheel, error)) return nullptr;
  reader->lidar_ = std::make_unique<Lidar>(lidar);
  drivers::PcapUdpFilter filter;
  filter.dst_ports = {lidar.msop_port, lidar.difop_port};
  reader->lidar_->pcap = drivers::PcapReader::Open((dir / "lidar.pcap").string(), filter, error);
  if (!reader->lidar_->pcap) return nullptr;
  return reader;
}

bool RecordingReader::ReadImu(const std::filesystem::path& dir,
                              const drivers::ImuConfig& imu,
                              bool gnss,
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
        const std::optional<ImuSample> s = stage.Map(ToImuRaw(m, t_rx, frame.frame_bytes));
        if (s) imu_.push_back(*s);
        if (!gnss || !m.gnss_pvt) continue;
        // The fix takes its message's IMU time; without one (a dropped sample) it has none.
        const std::optional<GnssFix> fix = s ? xs::ToGnssFix(*m.gnss_pvt, s->t_ns) : std::nullopt;
        if (fix) gnss_.push_back(*fix);
        (fix ? stats_.gnss_fixes : stats_.gnss_rejected)++;
      }
    }
  }
  stats_.imu_samples = imu_.size();
  stats_.imu_checksum_errors = framer.stats().checksum_errors;
  stats_.imu_skipped_bytes = framer.stats().skipped_bytes;
  stats_.imu_clock = stage.clock();
  return true;
}

bool RecordingReader::ReadWheel(const std::filesystem::path& dir,
                                const drivers::CanConfig& can,
                                std::string* error) {
  ConfigIssues issues;
  std::optional<drivers::WheelOdomDecoder> decoder =
      drivers::WheelOdomDecoder::Create(can, &issues);
  if (!decoder) {
    *error = "invalid wheel-odometry CAN layout:";
    for (const ConfigIssue& i : issues) *error += " " + i.key + ": " + i.reason + ";";
    return false;
  }
  std::ifstream in(dir / "can.log");
  if (!in) {
    stats_.wheel_log_missing = 1;
    return true;
  }
  drivers::CandumpReader log(in);
  drivers::CandumpRecord r;
  uint64_t unusable = 0;
  while (log.Next(&r)) {
    const std::optional<drivers::WheelOdomSample> s = decoder->Decode(r.frame, r.t_ns);
    if (!s) continue;
    const bool in_order = wheel_.empty() || s->t_ns >= wheel_.back().t_ns;
    if (!in_order || !std::isfinite(s->linear_velocity_mps) || !std::isfinite(s->yaw_rate_radps)) {
      ++unusable;
      continue;
    }
    wheel_.push_back({s->t_ns, s->linear_velocity_mps, s->yaw_rate_radps});
  }
  const drivers::CandumpCounters& lc = log.counters();
  const drivers::WheelOdomCounters& dc = decoder->counters();
  stats_.wheel_samples = wheel_.size();
  stats_.wheel_frames_dropped = lc.malformed_lines + lc.can_fd_lines +
                                (dc.frames - dc.frames_used) + dc.unpaired_dropped + unusable;
  return true;
}

bool RecordingReader::NextOptional(int64_t limit_ns, RecordingEvent* event) {
  const int64_t* t_imu = imu_next_ < imu_.size() ? &imu_[imu_next_].t_ns : nullptr;
  const int64_t* t_gnss = gnss_next_ < gnss_.size() ? &gnss_[gnss_next_].t_ns : nullptr;
  const int64_t* t_wheel = wheel_next_ < wheel_.size() ? &wheel_[wheel_next_].t_ns : nullptr;
  const bool gnss_first = NotAfter(t_gnss, t_wheel);
  const int64_t* t = gnss_first ? t_gnss : t_wheel;
  // Not yet due; an IMU sample goes before a fix or wheel sample of the same time.
  if (t == nullptr || *t > limit_ns || (t_imu != nullptr && *t_imu <= *t)) return false;
  if (gnss_first) {
    event->kind = RecordingEvent::Kind::kGnss;
    event->gnss = gnss_[gnss_next_++];
  } else {
    event->kind = RecordingEvent::Kind::kWheel;
    event->wheel = wheel_[wheel_next_++];
  }
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
  const int64_t limit_ns =
      have_scan_ ? pending_scan_.t_end_ns : std::numeric_limits<int64_t>::max();
  if (NextOptional(limit_ns, event)) return true;
  if (imu_next_ < imu_.size() && imu_[imu_next_].t_ns <= limit_ns) {
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

}  // namespace swlio::daemon

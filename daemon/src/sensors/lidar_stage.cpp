#include "swlio/daemon/sensors/lidar_stage.h"

#include <stdexcept>
#include <utility>

#include "swlio/drivers/lidar_decoder_factory.h"

namespace swlio::daemon {
namespace {

std::unique_ptr<drivers::LidarPacketDecoder> DecoderFor(const drivers::LidarConfig& config) {
  auto decoder = drivers::MakeLidarDecoder(config);
  if (!decoder) throw std::invalid_argument("unknown LiDAR model '" + config.model + "'");
  return decoder;
}

drivers::ScanAssemblerConfig AssemblerConfig(const drivers::LidarConfig& config,
                                             const drivers::LidarPacketDecoder& decoder) {
  drivers::ScanAssemblerConfig c;
  c.cut_angle_deg = config.cut_angle_deg;
  c.packets_per_revolution = decoder.PacketsPerRevolution();
  c.revolution_period_ns = config.rpm > 0.0 ? static_cast<int64_t>(60e9 / config.rpm) : 0;
  return c;
}

// What the kernel charges one LiDAR datagram against the socket's receive buffer: 2304 B for a
// 1248 B RS16 datagram (measured here on loopback: an 8 MiB grant held 3640 of them); VLP-16's
// 1206 B datagrams fall into the same 2 KiB allocation.
constexpr int64_t kDatagramChargeBytes = 2304;

drivers::ClockModelConfig LidarClockConfig(const drivers::LidarConfig& config,
                                           const drivers::LidarPacketDecoder& decoder) {
  drivers::ClockModelConfig c;
  c.fixed_latency_ns = 23 * 55'500 + 15 * 2'800;  // RS16: 55.5 µs sequences, 2.8 µs slots
  // A reader starved on a busy host finds datagrams queued in the socket, late by up to what
  // its receive buffer holds in time; that is a backlog, not the LiDAR's clock stepping back.
  // Linux grants twice the requested SO_RCVBUF (socket(7)). RS16 at 600 rpm with the default
  // 8 MiB request: 7282 datagrams, 8.7 s.
  const double rpm = config.rpm > 0.0 ? config.rpm : 600.0;
  const double datagrams_per_s = decoder.PacketsPerRevolution() * rpm / 60.0;
  if (datagrams_per_s > 0.0) {
    const double held = 2.0 * static_cast<double>(config.rcvbuf_bytes) / kDatagramChargeBytes;
    c.backlog_ns = static_cast<int64_t>(held / datagrams_per_s * 1e9);
  }
  return c;
}

}  // namespace

LidarStage::LidarStage(const drivers::LidarConfig& config)
    : decoder_(DecoderFor(config)),
      assembler_(AssemblerConfig(config, *decoder_)),
      clock_(LidarClockConfig(config, *decoder_)) {}

LidarStage::~LidarStage() = default;

void LidarStage::Add(std::span<const uint8_t> payload, int64_t t_rx_ns) {
  const drivers::LidarPacketKind kind = decoder_->Classify(payload);
  if (kind == drivers::LidarPacketKind::kInfo) {
    if (decoder_->DecodeInfo(payload) != drivers::DecodeStatus::kOk) {
      ++counters_.info_errors;
      return;
    }
    ++counters_.info_packets;
    const double rpm = decoder_->Rpm();
    assembler_.SetNominal(decoder_->PacketsPerRevolution(),
                          rpm > 0.0 ? static_cast<int64_t>(60e9 / rpm) : 0);
    return;
  }
  drivers::LidarPacketSummary summary;
  if (kind != drivers::LidarPacketKind::kData ||
      decoder_->DecodeData(payload, buffer_, &summary) != drivers::DecodeStatus::kOk) {
    ++counters_.bad_packets;
    return;
  }
  ++counters_.data_packets;
  clock_.Observe(summary.t_sensor_ns, t_rx_ns);
  assembler_.AddPacket(std::span(buffer_).first(summary.returns), summary, t_rx_ns);
}

void LidarStage::Flush() { assembler_.Flush(); }

bool LidarStage::Pop(HostSweep* out) {
  if (!assembler_.PopScan(&assembled_)) return false;
  std::swap(out->scan, assembled_.scan);
  // The points' dt_ns stay on the sensor's scale, so the end is the last point's time on the
  // same terms: start + span. Mapping the end through the drift too would put it up to
  // drift × 0.1 s (0.6 µs at 6 ppm) away from the last point, and a consumer that rebuilds the
  // sweep from its points (a PointCloud2 in a bag) could not tell.
  const int64_t span_ns = out->scan.t_end_ns - out->scan.t_start_ns;
  out->scan.t_start_ns = clock_.ToHost(out->scan.t_start_ns);
  out->scan.t_end_ns = out->scan.t_start_ns + span_ns;
  const int64_t overlap_ns = last_end_ns_ - out->scan.t_start_ns;
  if (overlap_ns > 0 && overlap_ns <= kMaxAbsorbedOverlapNs) {
    out->scan.t_start_ns += overlap_ns;  // points keep their dt_ns from the start
    out->scan.t_end_ns += overlap_ns;
    ++counters_.overlaps_absorbed;
  }
  last_end_ns_ = out->scan.t_end_ns;
  out->host_rx_last_ns = assembled_.host_rx_last_ns;
  out->missing_packets = assembled_.missing_packets;
  ++counters_.sweeps;
  counters_.partial_sweeps += out->scan.partial ? 1 : 0;
  counters_.missing_packets += assembled_.missing_packets;
  return true;
}

}  // namespace swlio::daemon

// Sweep assembly from decoded LiDAR packets, model-agnostic. Rules in scan_assembler.h.

#include "swlio/drivers/scan_assembler.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace swlio::drivers {
namespace {

double Wrap360(double deg) {
  deg -= 360.0 * std::floor(deg / 360.0);
  return deg >= 360.0 ? 0.0 : deg;
}

}  // namespace

ScanAssembler::ScanAssembler(const ScanAssemblerConfig& config) : config_(config) {
  SetNominal(config.packets_per_revolution, config.revolution_period_ns);
  current_.scan.points.reserve(config_.reserve_points);
}

void ScanAssembler::SetNominal(double packets_per_revolution, int64_t revolution_period_ns) {
  config_.packets_per_revolution = packets_per_revolution > 0.0 ? packets_per_revolution : 1.0;
  config_.revolution_period_ns = std::max<int64_t>(revolution_period_ns, 0);
}

double ScanAssembler::RelativeAzimuth(float azimuth_deg) const {
  double rel = static_cast<double>(azimuth_deg) - config_.cut_angle_deg;
  if (rel < 0.0) rel += 360.0;  // the usual case: both angles in [0, 360)
  return rel >= 0.0 && rel < 360.0 ? rel : Wrap360(rel);
}

void ScanAssembler::CheckContinuity(const LidarPacketSummary& summary) {
  const bool had_previous = have_previous_;
  const int64_t dt_ns = summary.t_sensor_ns - previous_t_ns_;
  const double az_step = Wrap360(static_cast<double>(summary.first_azimuth_deg) -
                                 static_cast<double>(previous_first_azimuth_deg_));
  have_previous_ = true;
  previous_t_ns_ = summary.t_sensor_ns;
  previous_first_azimuth_deg_ = summary.first_azimuth_deg;
  if (!had_previous) return;

  const double packet_ns =
      static_cast<double>(config_.revolution_period_ns) / config_.packets_per_revolution;
  const double packet_deg = 360.0 / config_.packets_per_revolution;
  const double tolerance = config_.gap_tolerance_packets;
  const bool time_known = config_.revolution_period_ns > 0;
  if (dt_ns <= 0 || (time_known && 2 * dt_ns >= config_.revolution_period_ns)) {
    ++stats_.discontinuities;
    if (dt_ns > 0) {  // a long forward jump: count what the time says is missing
      const double missing = std::round(static_cast<double>(dt_ns) / packet_ns) - 1.0;
      ++stats_.gaps;
      stats_.missing_packets += static_cast<uint64_t>(std::min(missing, 1e12));
    }
    if (current_open_) CloseCurrent(false);
    return;
  }
  double missing = 0.0;
  if (time_known && static_cast<double>(dt_ns) > tolerance * packet_ns) {
    missing = std::round(static_cast<double>(dt_ns) / packet_ns) - 1.0;
  }
  if (az_step > tolerance * packet_deg) {
    missing = std::max(missing, std::round(az_step / packet_deg) - 1.0);
  }
  if (missing < 1.0) return;
  ++stats_.gaps;
  const auto n = static_cast<uint32_t>(missing);
  stats_.missing_packets += n;
  if (current_open_) {
    current_.missing_packets += n;
  } else {
    pending_missing_ += n;
  }
}

void ScanAssembler::Advance(float azimuth_deg) {
  const double rel = RelativeAzimuth(azimuth_deg);
  double delta = rel - previous_relative_deg_;
  if (delta > 180.0) delta -= 360.0;
  if (delta <= -180.0) delta += 360.0;
  previous_relative_deg_ = rel;
  unwrapped_deg_ += delta;
  if (unwrapped_deg_ >= 360.0) {
    CloseCurrent(true);
    StartNew(true, rel);
  }
}

int ScanAssembler::AddPacket(std::span<const LidarReturn> returns,
                             const LidarPacketSummary& summary,
                             int64_t host_rx_ns) {
  ++stats_.packets;
  ++packet_id_;
  current_host_rx_ns_ = host_rx_ns;
  CheckContinuity(summary);
  if (current_open_) Advance(summary.first_azimuth_deg);
  for (const LidarReturn& r : returns) AddReturn(r);
  return ready_count_;
}

void ScanAssembler::AddReturn(const LidarReturn& r) {
  if (!current_open_) {
    StartNew(false, RelativeAzimuth(r.azimuth_deg));
  } else {
    Advance(r.azimuth_deg);
  }
  Scan& scan = current_.scan;
  if (scan.points.empty()) {
    scan.t_start_ns = r.t_sensor_ns;
    current_.first_azimuth_deg = r.azimuth_deg;
    current_.host_rx_first_ns = current_host_rx_ns_;
  }
  if (current_last_packet_id_ != packet_id_) {
    current_last_packet_id_ = packet_id_;
    ++current_.packets;
  }
  LidarPoint& pt = scan.points.emplace_back();
  pt.xyz_m = Eigen::Vector3f(r.x_m, r.y_m, r.z_m);
  pt.intensity = r.intensity;
  pt.ring = r.ring;
  pt.dt_ns = std::max<int64_t>(0, r.t_sensor_ns - scan.t_start_ns);
  scan.t_end_ns = std::max(scan.t_end_ns, r.t_sensor_ns);
  current_.last_azimuth_deg = r.azimuth_deg;
  current_.host_rx_last_ns = current_host_rx_ns_;
}

void ScanAssembler::StartNew(bool at_cut, double relative_azimuth_deg) {
  current_.scan.points.clear();
  if (current_.scan.points.capacity() < config_.reserve_points) {
    current_.scan.points.reserve(config_.reserve_points);
  }
  current_.scan.t_start_ns = 0;
  current_.scan.t_end_ns = 0;
  current_.scan.partial = false;
  current_.host_rx_first_ns = current_.host_rx_last_ns = 0;
  current_.packets = 0;
  current_.missing_packets = std::exchange(pending_missing_, 0u);
  current_.started_at_cut = at_cut;
  current_.ended_at_cut = false;
  current_last_packet_id_ = 0;
  previous_relative_deg_ = relative_azimuth_deg;
  unwrapped_deg_ = relative_azimuth_deg;
  current_open_ = true;
}

void ScanAssembler::CloseCurrent(bool ended_at_cut) {
  current_open_ = false;
  if (current_.scan.points.empty()) {
    pending_missing_ += current_.missing_packets;
    return;
  }
  current_.ended_at_cut = ended_at_cut;
  current_.scan.partial = !current_.started_at_cut || !ended_at_cut || current_.missing_packets > 0;
  current_.scan.seq = next_seq_++;
  ++stats_.scans;
  if (current_.scan.partial) ++stats_.partial_scans;
  if (ready_count_ == kMaxReady) {  // the consumer lags: drop the oldest
    ready_head_ = (ready_head_ + 1) % kMaxReady;
    --ready_count_;
    ++stats_.dropped_scans;
  }
  std::swap(ready_[static_cast<size_t>((ready_head_ + ready_count_) % kMaxReady)], current_);
  ++ready_count_;
}

int ScanAssembler::Flush() {
  if (current_open_) CloseCurrent(false);
  return ready_count_;
}

bool ScanAssembler::PopScan(AssembledScan* out) {
  if (ready_count_ == 0) return false;
  std::swap(*out, ready_[static_cast<size_t>(ready_head_)]);
  ready_head_ = (ready_head_ + 1) % kMaxReady;
  --ready_count_;
  return true;
}

}  // namespace swlio::drivers

#include "live/sim_faults.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "swlio/drivers/rs16_protocol.h"

namespace swlio::sim {

FaultInjector::FaultInjector(const LiveFaults& faults) : faults_(faults), rng_(faults.seed) {}

bool FaultInjector::InAny(const std::vector<TimeWindow>& windows, double t_s) {
  return std::any_of(windows.begin(), windows.end(),
                     [t_s](const TimeWindow& w) { return w.Contains(t_s); });
}

// Gilbert's two-state channel: every datagram in the bad state is lost. Leaving the bad state
// with p_bg = 1/burst gives bursts of that mean length; entering it with
// p_gb = f·p_bg/(1 − f) makes the long-run fraction in the bad state f.
bool FaultInjector::LoseMsop() {
  const double f = std::clamp(faults_.udp_loss_fraction, 0.0, 0.99);
  if (f <= 0.0) return false;
  const double p_bg = 1.0 / std::max(1.0, faults_.udp_loss_burst_packets);
  const double p_gb = f * p_bg / (1.0 - f);
  in_burst_ = in_burst_ ? rng_.Uniform() >= p_bg : rng_.Uniform() < p_gb;
  return in_burst_;
}

// Every slot with a return gets the same distance code (RS16 MSOP layout, rs16_protocol.h;
// the simulator writes the 5 mm resolution).
void FaultInjector::SetOneRange(std::span<uint8_t> bytes) {
  namespace rs16 = drivers::rs16;
  const auto code =
      static_cast<uint16_t>(std::lround(faults_.one_range_m / rs16::kDistanceResolutionM));
  for (size_t b = 0; b < rs16::kBlocks; ++b) {
    const size_t block = rs16::kFirstBlockOffset + b * rs16::kBlockBytes + 4;
    for (size_t s = 0; s < rs16::kSlotsPerBlock; ++s) {
      uint8_t* slot = bytes.data() + block + s * rs16::kSlotBytes;
      const auto raw = static_cast<uint16_t>(slot[0] << 8 | slot[1]);
      if (raw == rs16::kNoReturnZero || raw == rs16::kNoReturnMax) continue;
      slot[0] = static_cast<uint8_t>(code >> 8);
      slot[1] = static_cast<uint8_t>(code & 0xFF);
    }
  }
}

bool FaultInjector::PassDatagram(double t_s, bool difop, std::span<uint8_t> bytes) {
  if (faults_.lidar_silent || InAny(faults_.lidar_outages, t_s)) {
    (difop ? counts_.difop_dropped : counts_.msop_withheld)++;
    return false;
  }
  if (difop) {
    if (faults_.difop_missing) {
      ++counts_.difop_dropped;
      return false;
    }
    if (faults_.difop_corrupt && bytes.size() == drivers::rs16::kPacketBytes) {
      // Bit errors in the body (the header still says DIFOP): the calibration's bytes.
      for (int k = 0; k < 8; ++k) {
        const size_t at = drivers::rs16::kDifopPitchCali + rng_.Below(uint64_t{16} * 3);
        bytes[at] = static_cast<uint8_t>(bytes[at] ^ (1u << rng_.Below(8)));
      }
      ++counts_.difop_corrupted;
    }
    return true;
  }
  if (LoseMsop()) {
    ++counts_.msop_lost;
    return false;
  }
  if (bytes.size() == drivers::rs16::kPacketBytes && InAny(faults_.lidar_one_range, t_s)) {
    SetOneRange(bytes);
    ++counts_.msop_one_range;
  }
  return true;
}

bool FaultInjector::PassImu(double t_s, SimImuSample* sample) {
  if (faults_.imu_silent || InAny(faults_.imu_gaps, t_s) || Unplugged(t_s)) {
    ++counts_.imu_withheld;
    return false;
  }
  if (faults_.imu_nonfinite_fraction > 0.0 && rng_.Uniform() < faults_.imu_nonfinite_fraction) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const double bad[3] = {std::numeric_limits<double>::quiet_NaN(), kInf, -kInf};
    sample->acc_mps2[static_cast<Eigen::Index>(rng_.Below(3))] = bad[rng_.Below(3)];
    ++counts_.imu_nonfinite;
  }
  return true;
}

void FaultInjector::AppendGarbage(double t_s, std::vector<uint8_t>* out) {
  if (faults_.serial_garbage_bytes_per_s <= 0.0) return;
  if (last_garbage_t_s_ >= 0.0 && t_s > last_garbage_t_s_) {
    garbage_due_ += (t_s - last_garbage_t_s_) * faults_.serial_garbage_bytes_per_s;
  }
  last_garbage_t_s_ = t_s;
  for (; garbage_due_ >= 1.0; garbage_due_ -= 1.0) {
    out->push_back(static_cast<uint8_t>(rng_.Below(256)));
    ++counts_.garbage_bytes;
  }
}

}  // namespace swlio::sim

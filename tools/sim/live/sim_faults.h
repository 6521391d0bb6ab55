#pragma once
/// @file
/// Faults the live sender injects into what it streams (issue 9): what a substation's wiring,
/// connectors and sensors do to the daemon's inputs. Each is off by default; times are
/// simulation seconds (the route's clock, before the speed-up). A LiDAR clock jump is a
/// property of the sensor's clock instead (DeviceClock::step_at_s in imu_sim.h), an IMU counter
/// wrap one of the IMU clock's offset.

#include <cstdint>
#include <span>
#include <vector>

#include "rng.h"
#include "sensors/imu_sim.h"

namespace swlio::sim {

struct TimeWindow {
  double start_s = 0.0;
  double duration_s = 0.0;
  bool Contains(double t_s) const { return t_s >= start_s && t_s < start_s + duration_s; }
};

struct LiveFaults {
  /// MSOP datagrams lost in bursts: a two-state (Gilbert) channel with this long-run loss
  /// fraction and this mean burst length in datagrams.
  double udp_loss_fraction = 0.0;
  double udp_loss_burst_packets = 5.0;
  std::vector<TimeWindow> lidar_outages;   ///< nothing is sent on UDP (MSOP nor DIFOP)
  std::vector<TimeWindow> imu_gaps;        ///< the IMU's frames are not written (and lost)
  std::vector<TimeWindow> serial_unplugs;  ///< the pty goes away; a new one behind the same link
  /// The frames are written late, all at the window's end: what the host sees when the
  /// kernel's tty worker (or the USB host controller) is starved for that long. Nothing is lost.
  std::vector<TimeWindow> serial_stalls;
  std::vector<TimeWindow> lidar_one_range;  ///< every return reads `one_range_m` (a blocked lens)
  double one_range_m = 0.6;
  double serial_garbage_bytes_per_s = 0.0;  ///< random bytes written between frames
  double imu_nonfinite_fraction = 0.0;      ///< frames whose acceleration is NaN or ±Inf
  bool difop_missing = false;               ///< DIFOP packets are never sent
  bool difop_corrupt = false;               ///< DIFOP packets arrive with a damaged header
  bool lidar_silent = false;                ///< the LiDAR never starts
  bool imu_silent = false;                  ///< the IMU never starts
  uint64_t seed = 1;
};

/// What was injected, for the test to hold the daemon's counters against.
struct FaultCounts {
  uint64_t msop_lost = 0;      ///< by the loss channel
  uint64_t msop_withheld = 0;  ///< by outages and silence
  uint64_t difop_dropped = 0;
  uint64_t difop_corrupted = 0;
  uint64_t msop_one_range = 0;
  uint64_t imu_withheld = 0;  ///< frames not written (gaps, unplugged, silent)
  uint64_t imu_nonfinite = 0;
  uint64_t garbage_bytes = 0;
  uint64_t unplugs = 0;
};

class FaultInjector {
 public:
  explicit FaultInjector(const LiveFaults& faults);

  /// False: the datagram is not sent. Otherwise it may have been altered in place.
  bool PassDatagram(double t_s, bool difop, std::span<uint8_t> bytes);
  /// False: the sample's frame is not written. Otherwise its values may have been altered.
  bool PassImu(double t_s, SimImuSample* sample);
  /// Appends the garbage due since the previous call (at t_s) to `out`.
  void AppendGarbage(double t_s, std::vector<uint8_t>* out);
  bool Unplugged(double t_s) const { return InAny(faults_.serial_unplugs, t_s); }
  bool SerialStalled(double t_s) const { return InAny(faults_.serial_stalls, t_s); }

  const FaultCounts& counts() const { return counts_; }
  FaultCounts* mutable_counts() { return &counts_; }

 private:
  static bool InAny(const std::vector<TimeWindow>& windows, double t_s);
  bool LoseMsop();
  void SetOneRange(std::span<uint8_t> bytes);

  LiveFaults faults_;
  Rng rng_;
  FaultCounts counts_;
  bool in_burst_ = false;
  double garbage_due_ = 0.0;  ///< bytes owed (fractional)
  double last_garbage_t_s_ = -1.0;
};

}  // namespace swlio::sim

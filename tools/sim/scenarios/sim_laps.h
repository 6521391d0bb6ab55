#pragma once
/// @file
/// Driving a closed route (one that ends where and as it starts, e.g. `loop943`) lap after lap,
/// for long runs such as the soak: hours of driving from a route of minutes.
///
/// A lap lasts a whole number of LiDAR packet periods and of rotations, so that every lap's
/// packets carry the first lap's azimuths and fit the packet grid: lap k's packets are lap 0's
/// with header and receive times k laps later. `LidarLaps` casts the rays of lap 0 once and
/// replays them (ray casting runs at a few times real time on one core; replaying costs
/// almost nothing, so long runs can stream at 10×). The range noise then repeats every lap;
/// the IMU's noise does not (it is simulated over the whole run).

#include <cstdint>
#include <string>
#include <vector>

#include "scenarios/sim_setup.h"
#include "sensors/lidar_sim.h"

namespace swlio::sim {

/// The shortest lap period (s) that is at least the route's duration and a whole number of
/// MSOP packet periods and of rotations at the configured rpm.
double LapPeriodS(const SimSetup& setup);

/// Makes `setup` drive its route `laps` times (≥ 1), one lap every LapPeriodS. False with
/// `error` when the route does not end where and as it starts (the laps would not join up).
bool RepeatRoute(SimSetup* setup, int laps, std::string* error);

/// The LiDAR packets of a repeated route (RepeatRoute first), in receive order: the first lap
/// cast once at construction (minutes for loop943), the others replayed from memory (about
/// 1 GB for loop943).
class LidarLaps {
 public:
  explicit LidarLaps(const SimSetup& setup);

  /// The next packet; false after the last lap.
  bool Next(SimPacket* out);

  uint64_t msop_packets() const { return msop_sent_; }
  uint64_t difop_packets() const { return difop_sent_; }
  size_t packets_per_lap() const { return lap_.size(); }

 private:
  const SimSetup* setup_;
  double period_s_ = 0.0;
  int laps_ = 1;
  std::vector<SimPacket> lap_;
  size_t next_ = 0;
  int lap_index_ = 0;
  uint64_t msop_sent_ = 0;
  uint64_t difop_sent_ = 0;
};

}  // namespace swlio::sim

#include "scenarios/sim_laps.h"

#include <cmath>
#include <numeric>

#include "swlio/core/time.h"
#include "swlio/drivers/rs16_protocol.h"

namespace swlio::sim {

double LapPeriodS(const SimSetup& setup) {
  if (setup.trajectory->lap_period_s() > 0.0) return setup.trajectory->lap_period_s();
  const auto rotation_ns = static_cast<int64_t>(std::llround(60e9 / setup.lidar.rpm));
  // 1.332 ms and 100 ms (600 rpm): a lap is a multiple of 33.3 s.
  const int64_t step_ns = std::lcm(kMsopPeriodNs, rotation_ns);
  const double steps =
      std::ceil(setup.trajectory->duration_s() * 1e9 / static_cast<double>(step_ns));
  return steps * static_cast<double>(step_ns) * 1e-9;
}

bool RepeatRoute(SimSetup* setup, int laps, std::string* error) {
  if (laps < 1) {
    *error = "laps must be at least 1";
    return false;
  }
  if (setup->trajectory->lap_period_s() > 0.0) {
    *error = "the route is already repeated";
    return false;
  }
  if (laps == 1) return true;
  if (!setup->trajectory->EndsWhereItStarts()) {
    *error = "scenario " + setup->scenario.name +
             " does not end where and as it starts, so laps would not join up (loop943 does)";
    return false;
  }
  setup->trajectory->Repeat(laps, LapPeriodS(*setup));
  return true;
}

LidarLaps::LidarLaps(const SimSetup& setup) : setup_(&setup) {
  const double duration_s = setup.trajectory->duration_s();
  period_s_ =
      setup.trajectory->lap_period_s() > 0.0 ? setup.trajectory->lap_period_s() : duration_s;
  laps_ = static_cast<int>(std::lround(duration_s / period_s_));
  LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, setup.seed);
  SimPacket packet;
  while (lidar.Next(&packet) && packet.t_header_s < period_s_ - 1e-9) lap_.push_back(packet);
}

bool LidarLaps::Next(SimPacket* out) {
  if (next_ == lap_.size()) {
    next_ = 0;
    ++lap_index_;
  }
  if (lap_index_ >= laps_ || lap_.empty()) return false;
  *out = lap_[next_++];
  const bool is_difop = out->dst_port != setup_->lidar.msop_port;
  if (lap_index_ > 0) {
    const double shift_s = period_s_ * lap_index_;
    out->t_rx_ns += SecToNs(shift_s);
    out->t_header_s += shift_s;
    const int64_t t_device_ns = SecToNs(setup_->lidar.clock.ToDevice(out->t_header_s));
    namespace rs16 = drivers::rs16;
    rs16::WriteTime(out->bytes.data() + (is_difop ? rs16::kDifopTime : rs16::kTimeOffset),
                    rs16::TimeFormat::kYmd, t_device_ns);
  }
  (is_difop ? difop_sent_ : msop_sent_)++;
  return true;
}

}  // namespace swlio::sim

#include "sensors/wheel_sim.h"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "rng.h"
#include "swlio/core/exact_number.h"
#include "swlio/core/time.h"
#include "swlio/drivers/bytes.h"
#include "swlio/drivers/candump_log.h"

namespace swlio::sim {
namespace {

constexpr const char* kInterface = "can0";

int16_t ToRaw(double mps, double lsb) {
  const double raw = std::nearbyint(mps / lsb);
  return static_cast<int16_t>(std::clamp(raw, -32768.0, 32767.0));
}

drivers::CanSignalConfig WheelSignal(const WheelSimConfig& config,
                                     const char* role,
                                     int64_t byte_offset) {
  drivers::CanSignalConfig s;
  s.role = role;
  s.can_id = config.can_id;
  s.byte_offset = byte_offset;
  s.length_bits = 16;
  s.byte_order = "intel";
  s.is_signed = true;
  s.scale = config.scale_mps_per_lsb;
  s.dlc = 8;
  return s;
}

/// Measured rim speed: scale error, white noise, then the LSB.
double Measure(double true_mps, double scale_error, const WheelNoiseModel& n, Rng& rng) {
  const double v = (1.0 + scale_error) * true_mps + rng.Normal(n.speed_sigma_mps);
  return n.quantum_mps > 0.0 ? std::nearbyint(v / n.quantum_mps) * n.quantum_mps : v;
}

}  // namespace

BaseTwist TrueBaseTwist(const Kinematics& imu, const Eigen::Isometry3d& T_imu_base) {
  const Eigen::Matrix3d R_base_imu = T_imu_base.linear().transpose();
  const Eigen::Vector3d v_imu = imu.R_world_body.transpose() * imu.v_world;  // IMU axes
  BaseTwist t;
  t.v_base_mps = R_base_imu * (v_imu + imu.omega_body.cross(T_imu_base.translation()));
  t.omega_base_radps = R_base_imu * imu.omega_body;
  return t;
}

drivers::CanConfig WheelCanConfig(const WheelSimConfig& config) {
  drivers::CanConfig c;
  c.enabled = true;
  c.interface = kInterface;
  c.mode = "wheel_speeds";
  c.wheel_speed_unit = "mps";
  c.track_width_m = config.track_width_m;
  c.signals = {WheelSignal(config, "left_wheel_speed", 0),
               WheelSignal(config, "right_wheel_speed", 2)};
  return c;
}

drivers::CanFrame EncodeWheelFrame(const WheelSimConfig& config,
                                   double left_mps,
                                   double right_mps) {
  drivers::CanFrame f;
  f.id = config.can_id;
  f.dlc = 8;
  drivers::bytes::WriteU16Le(f.data.data(),
                             static_cast<uint16_t>(ToRaw(left_mps, config.scale_mps_per_lsb)));
  drivers::bytes::WriteU16Le(f.data.data() + 2,
                             static_cast<uint16_t>(ToRaw(right_mps, config.scale_mps_per_lsb)));
  return f;
}

std::vector<SimWheelSample> SimulateWheels(const Trajectory& trajectory,
                                           const WheelSimConfig& config,
                                           uint64_t seed) {
  Rng rng(seed ^ 0x57EE1ull);
  const WheelNoiseModel& n = config.noise;
  const double half_track = 0.5 * config.track_width_m;
  std::vector<SimWheelSample> out;
  for (int64_t k = 0;; ++k) {
    const double t_s = static_cast<double>(k) / config.rate_hz;
    if (t_s > trajectory.duration_s()) break;
    const BaseTwist twist = TrueBaseTwist(trajectory.At(t_s), config.T_imu_base);
    SimWheelSample s;
    s.t_true_ns = SecToNs(t_s);
    s.t_rx_ns = s.t_true_ns + SecToNs(rng.Uniform(n.latency_min_s, n.latency_max_s));
    s.v_base_mps = twist.v_base_mps;
    s.yaw_rate_radps = twist.omega_base_radps.z();
    const double v_x = twist.v_base_mps.x(), w_z = s.yaw_rate_radps;
    s.left_mps = Measure(v_x - w_z * half_track, n.scale_error_left, n, rng);
    s.right_mps = Measure(v_x + w_z * half_track, n.scale_error_right, n, rng);
    s.frame = EncodeWheelFrame(config, s.left_mps, s.right_mps);
    out.push_back(s);
  }
  return out;  // latency (≤ 3 ms) < period (20 ms): already in receive order
}

bool WriteCanLog(const std::vector<SimWheelSample>& samples,
                 int64_t host_start_ns,
                 std::ostream& out) {
  for (const SimWheelSample& s : samples) {
    const auto record = drivers::MakeCandumpRecord(host_start_ns + s.t_rx_ns, kInterface, s.frame);
    if (!drivers::WriteCandumpLine(out, record)) return false;
  }
  return static_cast<bool>(out);
}

bool WriteWheelTruth(const std::vector<SimWheelSample>& samples,
                     int64_t host_start_ns,
                     std::ostream& out) {
  out << "t_ns,v_x_mps,yaw_rate_radps\n";
  for (const SimWheelSample& s : samples) {
    out << host_start_ns + s.t_true_ns << ',' << ExactNumber(s.v_base_mps.x()) << ','
        << ExactNumber(s.yaw_rate_radps) << '\n';
  }
  return static_cast<bool>(out);
}

}  // namespace swlio::sim

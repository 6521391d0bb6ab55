#include "sensors/imu_sim.h"

#include <algorithm>
#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::sim {
namespace {

Eigen::Vector3d NormalVec(Rng& rng, double sigma) {
  const double x = rng.Normal(sigma), y = rng.Normal(sigma), z = rng.Normal(sigma);
  return {x, y, z};
}

/// Host receive times: each frame leaves the device after its transmission time and waits for
/// the next serial burst.
void AssignDelivery(std::vector<SimImuSample>& samples, const ImuSimConfig& config, Rng& rng) {
  auto tx_ns = [&config](const SimImuSample& s) {  // 8N1: 10 bits per byte
    const double bytes = config.frame_bytes + (s.has_gnss_pvt ? config.gnss_pvt_item_bytes : 0.0);
    return SecToNs(bytes * 10.0 / config.baud);
  };
  double burst_s = 0.0;
  size_t i = 0;
  while (i < samples.size()) {
    double period = config.delivery.burst_period_s +
                    rng.Uniform(-config.delivery.burst_jitter_s, config.delivery.burst_jitter_s);
    if (rng.Uniform() < config.delivery.stall_probability) period += config.delivery.stall_s;
    burst_s += std::max(period, 1e-4);
    const int64_t burst_ns = SecToNs(burst_s);
    while (i < samples.size() && samples[i].t_true_ns + tx_ns(samples[i]) <= burst_ns) {
      samples[i].t_rx_ns = burst_ns;
      ++i;
    }
  }
}

/// Marks the first sample at or after each GNSS epoch (ImuSimConfig::gnss_pvt_period_s).
void MarkGnssEpochs(std::vector<SimImuSample>& samples, const ImuSimConfig& config) {
  if (config.gnss_pvt_period_s <= 0.0) return;
  const int64_t period_ns = SecToNs(config.gnss_pvt_period_s);
  const int64_t first_ns = SecToNs(config.gnss_first_fix_s);
  int64_t next_epoch_ns = (std::max<int64_t>(first_ns, 0) + period_ns - 1) / period_ns * period_ns;
  for (SimImuSample& s : samples) {
    if (s.t_true_ns < next_epoch_ns) continue;
    s.has_gnss_pvt = true;
    next_epoch_ns = (s.t_true_ns / period_ns + 1) * period_ns;
  }
}

/// An MTi's strapdown integration rate: it samples and integrates at 2 kHz, then outputs the
/// integrals' means at the output rate (MTi 600-series documentation, "Signal processing and
/// algorithms": strapdown at up to 2000 Hz with coning and sculling compensation; Xsens
/// knowledge base, "Signal processing pipeline - fidelity of 400 Hz signal").
constexpr double kStrapdownRateHz = 2000.0;

struct IntervalMeans {
  Eigen::Vector3d acc_mps2, gyro_radps;
};

/// What the MTi outputs for (t0_s, t1_s] as Acceleration and RateOfTurn: dv/Δt and dq/Δt
/// (core/types.h). dq is the body's exact turn over the interval; dv sums the world velocity
/// change and gravity over the strapdown steps and is expressed in the interval's middle frame,
/// the frame the pre-integration turns a step's specific force with (preintegration.h).
IntervalMeans MeansOver(const Trajectory& trajectory,
                        double t0_s,
                        double t1_s,
                        const Eigen::Vector3d& gravity) {
  const double dt = t1_s - t0_s;
  const int steps = std::max(1, static_cast<int>(std::ceil(dt * kStrapdownRateHz - 1e-9)));
  const double h = dt / steps;
  const Eigen::Matrix3d R0 = trajectory.At(std::max(0.0, t0_s)).R_world_body;
  const Eigen::Matrix3d R1 = trajectory.At(std::max(0.0, t1_s)).R_world_body;
  Eigen::Vector3d dv_world = Eigen::Vector3d::Zero();
  for (int j = 0; j < steps; ++j) {
    dv_world += (trajectory.At(std::max(0.0, t0_s + (j + 0.5) * h)).a_world + gravity) * h;
  }
  const Eigen::Vector3d turn = lie::Log(R0.transpose() * R1);
  const Eigen::Matrix3d R_mid = R0 * lie::Exp(0.5 * turn);
  return {R_mid.transpose() * dv_world / dt, turn / dt};
}

}  // namespace

std::vector<SimImuSample> SimulateImu(const Trajectory& trajectory,
                                      const ImuSimConfig& config,
                                      uint64_t seed) {
  Rng rng(seed ^ 0x1A2B3C4Dull);
  const ImuNoiseModel& n = config.noise;
  const double dt = 1.0 / config.rate_hz;
  const double acc_sigma = n.acc_noise_density * std::sqrt(config.rate_hz);
  const double gyro_sigma = n.gyro_noise_density * std::sqrt(config.rate_hz);
  Eigen::Vector3d bias_acc = NormalVec(rng, n.acc_bias_initial_sigma);
  Eigen::Vector3d bias_gyro = NormalVec(rng, n.gyro_bias_initial_sigma);
  const Eigen::Vector3d gravity(0.0, 0.0, config.gravity_mps2);
  // A device tick's interval in true time (a clock step relabels the ticks, it is no motion).
  const double interval_s = dt / (1.0 + config.clock.drift_ppm * 1e-6);

  std::vector<SimImuSample> out;
  // Device ticks start at the first 1/rate boundary of the device clock after host time 0.
  const double device_start = std::ceil(config.clock.ToDevice(0.0) * config.rate_hz) * dt;
  for (int64_t k = 0;; ++k) {
    const double device_s = device_start + static_cast<double>(k) * dt;
    const double host_s = config.clock.ToHost(device_s);
    if (host_s > trajectory.duration_s()) break;
    const double t_meas = host_s - config.time_offset_s;
    SimImuSample s;
    s.t_true_ns = SecToNs(host_s);
    s.sample_time_fine =
        static_cast<uint32_t>(static_cast<uint64_t>(std::llround(device_s * 1e4)) & 0xFFFFFFFFull);
    s.packet_counter = static_cast<uint16_t>(k & 0xFFFF);
    s.bias_acc = bias_acc;
    s.bias_gyro = bias_gyro;
    if (config.temperature.on) {
      s.bias_acc += ImuTemperatureAccBias(config.temperature, host_s);
      s.bias_gyro += ImuTemperatureGyroBias(config.temperature, host_s);
    }
    const IntervalMeans m = MeansOver(trajectory, t_meas - interval_s, t_meas, gravity);
    s.acc_mps2 = m.acc_mps2 + s.bias_acc + NormalVec(rng, acc_sigma);
    s.gyro_radps = m.gyro_radps + s.bias_gyro + NormalVec(rng, gyro_sigma);
    out.push_back(s);
    bias_acc += NormalVec(rng, n.acc_bias_random_walk * std::sqrt(dt));
    bias_gyro += NormalVec(rng, n.gyro_bias_random_walk * std::sqrt(dt));
  }
  MarkGnssEpochs(out, config);
  AssignDelivery(out, config, rng);
  return out;
}

}  // namespace swlio::sim

#pragma once
/// @file
/// MTi-G-710-like IMU: samples on the device's own clock (SampleTimeFine, 10 kHz ticks) with
/// offset and drift against host time, each the mean specific force and rate over its output
/// interval as the MTi's 2 kHz strapdown integration gives them (dv/Δt, dq/Δt: core/types.h);
/// white noise and bias random walk; gravity; serial delivery in USB-like bursts.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "rng.h"
#include "scenarios/trajectory.h"
#include "sensors/imu_temperature.h"

namespace swlio::sim {

/// Noise model. Defaults: Xsens MTi-G-710 datasheet (MTi 100-series): gyro noise density
/// 0.01 °/s/√Hz, accelerometer 60 µg/√Hz, gyro in-run bias stability 10 °/h; random walks chosen
/// to give that order of drift over minutes.
struct ImuNoiseModel {
  double acc_noise_density = 60e-6 * 9.80665;                       ///< m/s²/√Hz
  double gyro_noise_density = 0.01 * std::numbers::pi / 180.0;      ///< rad/s/√Hz
  double acc_bias_random_walk = 2e-5;                               ///< m/s³/√Hz
  double gyro_bias_random_walk = 2e-6;                              ///< rad/s²/√Hz
  double acc_bias_initial_sigma = 0.02;                             ///< m/s², per axis
  double gyro_bias_initial_sigma = 0.1 * std::numbers::pi / 180.0;  ///< rad/s, per axis
};

/// Device clock: device_time = (1 + drift_ppm·1e-6) · host_time + offset, plus `step_s` from
/// host time `step_at_s` on (a clock set anew, e.g. when GPS time arrives; a fault to inject).
struct DeviceClock {
  double offset_s = 0.0;
  double drift_ppm = 0.0;
  double step_at_s = std::numeric_limits<double>::infinity();
  double step_s = 0.0;
  double ToDevice(double host_s) const {
    return (1.0 + drift_ppm * 1e-6) * host_s + offset_s + (host_s >= step_at_s ? step_s : 0.0);
  }
  /// Inverse of ToDevice; where a backward step makes it ambiguous, the later host time.
  double ToHost(double device_s) const {
    const double stepped = (device_s - offset_s - step_s) / (1.0 + drift_ppm * 1e-6);
    if (stepped >= step_at_s) return stepped;
    return (device_s - offset_s) / (1.0 + drift_ppm * 1e-6);
  }
};

/// How the serial link delivers frames: in bursts every `burst_period_s` (± jitter), with an
/// occasional long stall (the USB host controller, the adapter's latency timer).
struct SerialDelivery {
  double burst_period_s = 0.004;
  double burst_jitter_s = 0.001;
  double stall_probability = 0.002;  ///< per burst
  double stall_s = 0.030;
};

struct SimImuSample {
  /// Host time its SampleTimeFine stands for (ground truth): the end of the interval it
  /// measures the motion of, shifted by ImuSimConfig::time_offset_s (the interval ends at
  /// t_true_ns − time_offset_s).
  int64_t t_true_ns = 0;
  int64_t t_rx_ns = 0;            ///< host time at which its frame arrives over serial
  uint32_t sample_time_fine = 0;  ///< device clock, 100 µs ticks, wraps at 2³²
  uint16_t packet_counter = 0;
  Eigen::Vector3d acc_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d bias_acc = Eigen::Vector3d::Zero();   ///< truth
  Eigen::Vector3d bias_gyro = Eigen::Vector3d::Zero();  ///< truth
  bool has_gnss_pvt = false;  ///< its MTData2 message also carries GnssPvtData (gnss_sim.h)
};

struct ImuSimConfig {
  double rate_hz = 400.0;
  double gravity_mps2 = 9.80665;
  ImuNoiseModel noise;
  DeviceClock clock;
  SerialDelivery delivery;
  double frame_bytes = 60.0;  ///< for the transmission time at `baud`
  double baud = 921600.0;
  /// GnssPvtData output (gnss_sim.h): the first sample at or after each multiple of this period
  /// of GNSS time (taken as the simulation's time) carries the item, from `gnss_first_fix_s`
  /// on; 0: no GNSS items (--no-gnss). 4 Hz: the MTi-G-710's GNSS output rate. The first fix
  /// comes after 1 s, a u-blox M8's hot-start time to first fix (u-blox MAX-M8 data sheet).
  double gnss_pvt_period_s = 0.25;
  double gnss_first_fix_s = 1.0;
  /// Bytes a GnssPvtData item adds to a frame (XDI, size, 94 bytes of data), which lengthen its
  /// transmission.
  double gnss_pvt_item_bytes = 3.0 + 94.0;
  /// An unknown LiDAR–IMU time offset (the `time_offset` disturbance): each sample measures the
  /// motion of `time_offset_s` before the host time its SampleTimeFine stands for (a filter
  /// delay or a constant serial latency the clock model cannot see; negative: after).
  double time_offset_s = 0.0;
  /// Bias drift with the device's temperature (the `temperature` disturbance).
  ImuTemperatureConfig temperature;
};

/// Samples over [0, duration] host seconds, in order; deterministic for a seed.
std::vector<SimImuSample> SimulateImu(const Trajectory& trajectory,
                                      const ImuSimConfig& config,
                                      uint64_t seed);

}  // namespace swlio::sim

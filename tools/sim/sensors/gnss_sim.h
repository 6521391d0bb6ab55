#pragma once
/// @file
/// The MTi-G-710's GNSS receiver: GnssPvtData items (XDI 0x7010, u-blox NAV-PVT layout and
/// units; drivers/xsens/mtdata2.h) in the MTData2 message of the IMU samples that
/// ImuSimConfig::gnss_pvt_period_s marks (4 Hz by default, the MTi-G-710's GNSS output rate).
///
/// Frames: the simulator's world frame is the local ENU frame (x east, y north, z up) at
/// `origin` (swlio/core/geodetic.h). The antenna sits at `p_imu_antenna_m` in the IMU frame:
///   p_enu_antenna = p_world_imu + R_world_imu · p_imu_antenna.
/// A fix is the antenna's position at the true time of the IMU sample that carries it, so a
/// reader that stamps the fix with that sample's host time has it exactly.
///
/// Errors: first-order Gauss–Markov processes per axis (east, north, up),
///   e_k = φ e_{k−1} + σ √(1 − φ²) w_k,   φ = exp(−Δt / τ),   w_k ~ N(0, 1),   e_0 ~ N(0, σ²),
/// stationary σ = sigma_h_m (east, north) and sigma_v_m (up). Their defaults (0.8 m, 1.5 m,
/// τ = 30 s) are assumed for an SBAS-aided u-blox M8-class receiver under open sky; the MTi
/// User Manual (MT0605P rev. E, §4.4, MTi-G-700) specifies its receiver's 4 Hz solution with
/// SBAS as 2.0 m CEP horizontal and 5.0 m CEP vertical (a CEP of 2.0 m is σ ≈ 1.7 m per axis),
/// and velocity 0.1 m/s 1σ RMS.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "live/sim_faults.h"
#include "scenarios/trajectory.h"
#include "sensors/imu_sim.h"
#include "swlio/core/geodetic.h"
#include "swlio/drivers/xsens/mtdata2.h"

namespace swlio::sim {

/// A multipath-like outlier: the reported position is `east_m` further east during the window
/// while the receiver's accuracy estimate stays as small as ever.
struct GnssJump {
  double start_s = 0.0;
  double duration_s = 0.0;
  double east_m = 0.0;
  bool Contains(double t_s) const { return t_s >= start_s && t_s < start_s + duration_s; }
};

struct GnssErrorModel {
  double sigma_h_m = 0.8;            ///< stationary σ of the east and of the north error
  double sigma_v_m = 1.5;            ///< stationary σ of the up error
  double correlation_time_s = 30.0;  ///< τ of the Gauss–Markov processes
  double velocity_sigma_mps = 0.05;  ///< white noise per NED axis. Assumed
  /// The receiver's reported accuracies: hAcc = inflation · √2 · σ_h (the 2-D RMS, inflated),
  /// vAcc = inflation · σ_v, sAcc = inflation · √3 · σ_vel. Receivers' own estimates are on the
  /// pessimistic side; 1.2 is assumed.
  double accuracy_inflation = 1.2;
};

struct GnssSimConfig {
  Geodetic origin{31.0, 121.0, 10.0};  ///< the world frame's origin (ellipsoidal height)
  Eigen::Vector3d p_imu_antenna_m{-0.20, 0.0, 0.45};  ///< lever arm, IMU frame
  GnssErrorModel noise;
  uint8_t num_sv = 12;
  /// UTC (Unix seconds) at simulation time 0: 2024-01-01T00:00:00Z. GPS time is UTC + 18 s.
  int64_t utc_start_unix_s = 1'704'067'200;
  /// No fix during these windows: the items keep coming with fixType 0 and gnssFixOK clear
  /// (as a u-blox receiver keeps sending NAV-PVT), holding the last position.
  std::vector<TimeWindow> outages;
  std::vector<GnssJump> jumps;
};

/// One GnssPvtData item with its truth.
struct SimGnssFix {
  size_t imu_index = 0;   ///< the IMU sample (SimulateImu's order) whose message carries it
  int64_t t_true_ns = 0;  ///< sim time of the position
  Eigen::Vector3d p_enu_true_m = Eigen::Vector3d::Zero();  ///< the antenna, truth
  Eigen::Vector3d error_enu_m = Eigen::Vector3d::Zero();   ///< reported − true (with a jump)
  bool has_fix = true;                                     ///< false during an outage
  drivers::xsens::XsensGnssPvt pvt;
};

/// The fixes of every sample with `has_gnss_pvt`, in order; deterministic for a seed.
std::vector<SimGnssFix> SimulateGnss(const Trajectory& trajectory,
                                     const GnssSimConfig& config,
                                     const std::vector<SimImuSample>& imu,
                                     uint64_t seed);

/// The antenna's true position in the world (ENU) frame.
Eigen::Vector3d TrueAntennaEnu(const Kinematics& imu, const Eigen::Vector3d& p_imu_antenna_m);

}  // namespace swlio::sim

#pragma once
/// @file
/// Options of the tightly coupled window (window_estimator.h), apart from the estimator so that
/// configuration code does not pull in Ceres.

#include <cstddef>
#include <cstdint>

#include "swlio/core/config_issue.h"
#include "swlio/estimator/imu/imu_noise_adapter.h"
#include "swlio/estimator/init/dynamic_bootstrap.h"
#include "swlio/estimator/registration/lidar_odometry.h"
#include "swlio/estimator/wheel/wheel_factor_config.h"
#include "swlio/estimator/window/divergence_monitor.h"
#include "swlio/estimator/window/standstill.h"
#include "swlio/estimator/window/time_offset_estimator.h"

namespace swlio::estimator {

struct WindowEstimatorConfig {
  /// Front end, matcher (association), maps, keyframes, extrinsic, noise and gravity.
  LidarOdometryConfig odometry;
  size_t window_size = 5;  ///< frames in the window (after marginalization)
  int max_iterations = 4;  ///< Ceres iterations per solve
  /// Re-associations of the newest frame at most after the window solve (each one more solve);
  /// they stop once a solve moves the pose less than matcher.reassociate_*.
  int reassociations = 1;
  /// Edge features of the window's sweeps (and its dynamic bootstrap), in place of
  /// odometry.front_end.features' edge_threshold_m2 and max_edges_per_sector; by default the
  /// LiDAR-only mode's. More and weaker edges (0.15 m², 40 per sector) trade along-track
  /// velocity for yaw (docs/notes/2026-11-24-loop943-yaw-drift.md, "The yaw drift"): loop943
  /// seeds 1–3 without loop closure, APE 0.716 / 0.360 / 0.664 → 0.454 / 0.198 / 0.372 m, yaw
  /// drift 0.285 → 0.231°/100 m; but on run_command_test's 25 s drive the forward velocity error
  /// 0.016 → 0.027 m/s RMS and its NEES 5.3 → 16 (limit 9). At 0.2 m² loop943 was worse than
  /// both (0.724 / 0.537 / 0.766 m): the gain is not established by three runs.
  double edge_threshold_m2 = 0.3;
  int64_t max_edges_per_sector = 20;
  /// Radius of the window's local maps (in place of odometry.estimator.local_map_radius_m, the
  /// LiDAR-only mode's 80 m): voxels farther from the robot are dropped. A map that keeps the
  /// whole site lets a revisited place match the surfaces first mapped there, and holds far
  /// surfaces that steady the yaw (docs/notes/2026-12-01-whole-site-local-map.md): loop943
  /// seeds 1–3 without loop closure, APE 0.406 / 0.240 / 0.475 m at 80 m → 0.062 / 0.077 /
  /// 0.150 m, end gap ≤ 0.02 m. LiDAR-only has drifted too far when it comes back and gains
  /// nothing (0.83 / 0.96 / 0.66 → 1.08 / 0.72 / 0.94 m), so its mode keeps 80 m.
  double local_map_radius_m = 250.0;
  double lidar_sigma_m = 0.05;  ///< point-to-plane / point-to-line standard deviation
  double huber_m = 0.1;         ///< Huber kernel width (metres of residual)
  /// When the newest state is not believable: re-initialize (divergence_monitor.h).
  DivergenceConfig divergence;
  /// A direction of the newest frame's LiDAR Hessian (ScanMatcher units: Σ JᵀJ over unwhitened
  /// residuals in metres, tangent [δp; δφ]) with a smaller eigenvalue is degenerate: its LiDAR
  /// row is left out and the IMU carries the estimate there (σ along it would be
  /// lidar_sigma_m / √eigenvalue).
  double degenerate_eigenvalue = 5.0;
  /// Floor under the covariance of a frame's LiDAR pose (see CompressLidar): the local map's own
  /// error, which more matched points do not reduce. Per world axis for position; for attitude
  /// split into tilt (roll/pitch, which gravity observes through the IMU: a loose floor lets the
  /// IMU keep the map level) and yaw (which only the LiDAR observes).
  double lidar_floor_sigma_m = 0.01;
  double lidar_floor_sigma_tilt_rad = 0.03;
  double lidar_floor_sigma_yaw_rad = 0.003;
  /// Weak prior about the configured extrinsic when it is estimated online.
  double extrinsic_prior_sigma_m = 0.02;
  double extrinsic_prior_sigma_rad = 0.01;
  /// Online extrinsic calibration (extrinsic_calibration_run.h): after this many seconds of
  /// LiDAR-only odometry beside the window (0: off), T_imu_lidar is calibrated in one batch and
  /// the window restarts on it; retried every calibrate_retry_s until the motion (turns)
  /// determines the rotation.
  double calibrate_extrinsic_s = 0.0;
  double calibrate_retry_s = 5.0;
  /// Prior of the first frame after the initialization: pose (gauge), velocity, biases. After a
  /// standing start the tilt's is the larger of init_sigma_rotation_rad and
  /// init_sigma_bias_acc_mps2 / g (StaticStartTiltSigma); after a moving start, the alignment's.
  double init_sigma_position_m = 1e-3;
  double init_sigma_rotation_rad = 1e-3;
  double init_sigma_velocity_mps = 0.05;
  double init_sigma_bias_acc_mps2 = 0.05;
  /// After a moving start, and when the window restarts from a running frame (a failed
  /// marginalization, an online calibration); a standing start (also the one after a recovery)
  /// takes the static initializer's standard error of the mean rate instead
  /// (StaticInitResult::bias_gyro_std).
  double init_sigma_bias_gyro_radps = 0.005;
  /// Weak absolute prior (about zero) on every window frame's biases, not marginalized: keeps
  /// b_a from absorbing a tilt of the local map (measured on `aggressive` without it: b_a
  /// wandered to 0.25 m/s², the simulated IMU's are ~0.02). 0 disables each.
  double bias_prior_sigma_acc_mps2 = 0.05;
  /// Off by default: at rest with no LiDAR features a gyro-bias prior about zero pulled the
  /// initializer's b_g away (window_estimator_test).
  double bias_prior_sigma_gyro_radps = 0.0;

  /// A static initialization needs the LiDAR to agree (with `dynamic_init`): registered speed
  /// below this.
  double static_max_speed_mps = 0.05;
  DynamicBootstrapConfig bootstrap;
  /// Wheel odometry from the chassis as a velocity factor on every frame (off by default).
  WheelFactorConfig wheel;
  /// A frame at rest (IMU and LiDAR agree) gets a zero-velocity factor (standstill.h).
  StandstillConfig standstill;
  /// The IMU factors' white-noise densities measured from the data (imu_noise_adapter.h; off).
  ImuNoiseAdapterConfig imu_noise_adapter;
  /// The LiDAR–IMU time offset estimated online and applied to the IMU samples (on by default;
  /// time_offset_estimator.h).
  TimeOffsetConfig time_offset;
  /// Moving objects out of the local maps (visibility_image.h): each keyframe's sweep tests
  /// the map points within check_radius_m, and points it sees through leave the maps; the
  /// keyframe carries its image to loop closure (KeyframeCloud::visibility).
  VisibilityConfig visibility;
  // Flags last (padding).
  /// Before the window solve, the newest frame is registered alone from the IMU prediction
  /// (ScanMatcher::Match, as the LiDAR-only mode does) and associated at that pose: the window
  /// solve alone, associated at the prediction, diverged on degenerate_2 (33 m APE).
  bool prealign = true;
  /// Refine T_imu_lidar in the window (tied to the configured value by the prior below).
  bool estimate_extrinsic = false;
  /// A robot already moving at start: until the static initializer sees it stand still,
  /// sweeps go through DynamicBootstrap (LiDAR-only registration aligned to the IMU); the first
  /// of the two to finish initializes the window. `bootstrap.odometry` is taken from `odometry`.
  bool dynamic_init = true;
  /// Compute the newest state's marginal covariance for every result (WindowResult).
  bool covariance = true;
  /// The first frame's tilt prior correlated with b_a as the accelerometer leaves them
  /// (initial_prior.h) instead of the diagonal prior (tilt to init_sigma_rotation_rad, b_a
  /// independent). More honest about the start's tilt (short_1 tilt NEES 5.9 → 3.5), but the
  /// tilt then moves while the early map keeps the start's, which bends long drives: APE
  /// loop943 seeds 1–3 0.454 / 0.620 / 0.458 → 0.628 / 0.613 / 0.708 m. Off by default.
  bool init_tilt_follows_bias = false;
  /// Estimate where gravity points in the map frame (gravity_tilt_imu_factor.h): the IMU factors
  /// take the map's tilt against gravity as one more block (2 angles, prior σ
  /// init_sigma_bias_acc_mps2 / g: the horizontal bias a standing start cannot tell from tilt).
  /// The map and the output stay in the first frame's (slightly tilted) frame; the tilt is in
  /// WindowResult, the covariance of the attitude against gravity in
  /// StateCovariance::rot_gravity. Without it, the tilt learned at the first turn is forced onto
  /// new frames against the start's map (loop943_3 ended 1.07 m high; ARCHITECTURE.md).
  /// With the 250 m local map, APE off → on (docs/notes/2026-12-01-whole-site-local-map.md):
  /// degenerate seeds 1–3 0.026 / 0.025 / 0.132 → 0.013 / 0.015 / 0.021 m, loop943 0.062 /
  /// 0.077 / 0.150 → 0.061 / 0.073 / 0.084 m; on run_command_test's drive the tilt NEES
  /// against gravity is 2.95 (off: 5.58, limit 6) and the velocity NEES 1.97
  /// (docs/notes/2026-11-22-covariance-and-nees.md, "The tilt NEES against gravity").
  bool estimate_gravity_tilt = true;

  ConfigIssues Validate() const;
};

/// `config` with its edge settings (edge_threshold_m2, max_edges_per_sector) put into
/// odometry.front_end.features, where the front end reads them, and its local_map_radius_m
/// into odometry.plane_map and edge_map.
WindowEstimatorConfig WithWindowFeatures(WindowEstimatorConfig config);

/// The first frame's roll/pitch σ after a standing start: the static initialization reads the
/// accelerometer's horizontal bias as tilt, b_a / g of it (0.29° for b_a 0.05 m/s²). With the
/// tighter gauge σ the estimate claimed 0.06° while off by the simulated bias's 0.17° for a
/// whole straight drive, once standstill stopped the early velocity errors from moving it
/// (`short` seed 11: tilt NEES 9.1, over the consistency test's 6).
double StaticStartTiltSigma(const WindowEstimatorConfig& config);

}  // namespace swlio::estimator

#pragma once
/// @file
/// Dynamic initialization (the robot already moving): aligns a short window of LiDAR-only
/// odometry poses with the IMU to recover gravity, per-frame velocity and the IMU biases.
///
/// The method is the visual-inertial alignment of VINS-Mono (Qin, Li, Shen, "VINS-Mono: A Robust
/// and Versatile Monocular Visual-Inertial State Estimator", IEEE T-RO 2018, §V-B: gyroscope
/// bias calibration, then a linear solve for velocities and gravity, then gravity refinement on
/// its 2-DoF tangent with |g| fixed), with two differences: LiDAR poses are metric, so there is
/// no scale unknown; and the LiDAR poses enter as measurements with their own noise.
///
/// Inputs: poses T_w0_lidar_k (k = 0..N) in the odometry's own world w0 (not gravity-aligned),
/// the IMU samples covering [t_0, t_N] and the extrinsic T_imu_lidar. IMU poses in w0:
///   R_k = R_w0_lidar_k · R_imu_lidarᵀ,   p_k = t_w0_lidar_k − R_k · t_imu_lidar (lever arm).
/// Pre-integration (preintegration.h) between consecutive frames gives ΔR, Δv, Δp with bias
/// Jacobians J; g below is the gravity acceleration vector in w0 (pointing down, |g| = G).
///
/// (1) Gyro bias. Compose the intervals into ΔR_0k with J_0k (ΔR_0,k+1 = ΔR_0k ΔR_k,
///     J_0,k+1 = ΔR_kᵀ J_0k + J_k). If frame 0's measured attitude is off by Exp(θ) (right),
///       y_k = Log(ΔR_0k(b̄_g)ᵀ R_0ᵀ R_k) ≈ ΔR_0kᵀ θ + J_0k δb_g + n_k,
///     with n_k the LiDAR attitude noise. Least squares over k = 1..N plus the row θ ≈ 0 (frame
///     0's own noise) fits a "line" through all frames (better than VINS-Mono's consecutive
///     pairs, which telescope to the two end frames). Iterated with re-integration.
/// (2) Linear solve, unknowns x = [p_0..p_N, v_0..v_N, g] (LiDAR positions as measurements):
///       p_k = p_k^lidar                                        (σ = position_sigma_m)
///       p_j − p_i − Δt v_i − ½Δt² g = R_i Δp_ij                 (IMU, σ from the covariance)
///       v_j − v_i − Δt g           = R_i Δv_ij                  (IMU)
///     The unconstrained |g| must match G (a check of extrinsic, timing and odometry).
/// (3) Refinement: g = G · normalize(ĝ + B δ), B a 3×2 tangent basis of ĝ, δ (rad) the tilt;
///     the accelerometer bias joins (Δv += J_v_ba b_a, Δp += J_p_ba b_a) with the prior
///     b_a ≈ 0 (σ = acc_bias_prior_sigma_mps2). Iterated, ĝ ← normalize(ĝ + B δ).
///     Observability comes from the posterior covariance H⁻¹: along straight constant-velocity
///     motion g − R b_a is seen only as a sum, so the horizontal part of b_a stays at its prior
///     (≈ 0, flagged unobservable) and the tilt uncertainty grows to ≈ σ_prior / G (honest).
///     Rotation (turns, roll/pitch) separates them.
/// (4) World: R_world_w0 rotates −ĝ onto +z, then about z so that the first IMU frame has
///     yaw 0 (as StaticInitializer and VINS-Mono do); its origin is the first IMU position.
///
/// Gravity and velocity are observable from any motion (positions are metric): failure comes
/// from inconsistent inputs (time offset, wrong lever arm, odometry slips: large normalized
/// residuals, an implausible gyro bias, wrong |g|) or from too weak constraints (few frames,
/// noisy poses: tilt or velocity standard deviation over the limits). Not detectable here: an
/// error of the extrinsic ROTATION passes into the gravity direction in w0 about 1:1 (the IMU's
/// own roll/pitch stay right); it needs the online extrinsic estimation.
/// Pure library: no clocks, no printing.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/estimator/common/estimator_config.h"

namespace swlio::estimator {

/// One LiDAR-odometry pose in the odometry's own world frame w0.
struct StampedLidarPose {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_w0_lidar = Eigen::Isometry3d::Identity();
  /// The registration's Gauss–Newton Hessian at this pose (MatchResult::hessian: unit-weight
  /// residuals, right perturbation [ρ; φ]); zero when unknown. Only the extrinsic calibration
  /// uses it, to weight each pose by what its scan determined.
  Eigen::Matrix<double, 6, 6> hessian = Eigen::Matrix<double, 6, 6>::Zero();
};

enum class DynamicInitStatus {
  kOk,
  kTooFewFrames,       ///< fewer than Options::min_frames poses
  kBadInput,           ///< pose times not strictly increasing, or non-finite values
  kImuNotCovered,      ///< the IMU samples do not span the poses (or are unsorted)
  kInconsistent,       ///< residuals or |g| beyond the limits: extrinsic, time or odometry wrong
  kPoorlyConstrained,  ///< tilt or velocity uncertainty beyond the limits (or b_a if required)
};

/// Human-readable reason for a status.
std::string_view DynamicInitStatusReason(DynamicInitStatus status);

struct DynamicInitResult {
  DynamicInitStatus status = DynamicInitStatus::kTooFewFrames;
  /// One state per pose (IMU frame at the pose time) in the gravity-aligned world; filled
  /// whenever the solve ran (also for kInconsistent / kPoorlyConstrained, for diagnosis).
  std::vector<State> states;
  /// Maps the odometry world w0 into the gravity-aligned world: T_world_lidar = T_world_w0 ·
  /// T_w0_lidar (to carry the odometry's map over).
  Eigen::Isometry3d T_world_w0 = Eigen::Isometry3d::Identity();
  Eigen::Vector3d gravity_w0 = Eigen::Vector3d::Zero();  ///< gravity acceleration in w0, m/s²
  Eigen::Vector3d bias_gyro = Eigen::Vector3d::Zero();   ///< rad/s
  Eigen::Vector3d bias_acc = Eigen::Vector3d::Zero();  ///< m/s²; prior (≈ 0) where unobservable
  bool acc_bias_observable = false;  ///< every direction's std ≤ max_acc_bias_std_mps2
  // Quality figures.
  Eigen::Vector3d bias_acc_std = Eigen::Vector3d::Zero();   ///< per-axis posterior std, m/s²
  Eigen::Vector3d bias_gyro_std = Eigen::Vector3d::Zero();  ///< per-axis posterior std, rad/s
  double gravity_tilt_std_rad = 0.0;        ///< largest std of the gravity direction
  double velocity_std_mps = 0.0;            ///< largest std of the last frame's velocity
  double gravity_norm_free_mps2 = 0.0;      ///< |g| of the unconstrained solve (2)
  double gravity_norm_free_std_mps2 = 0.0;  ///< its standard deviation
  double rotation_rms_rad = 0.0;            ///< LiDAR-vs-IMU attitude residual after (1)
  double position_rms_m = 0.0;              ///< LiDAR position residual after (3)
  double normalized_cost = 0.0;             ///< whitened cost / degrees of freedom after (3)
  double condition_number = 0.0;            ///< of the Jacobi-scaled normal matrix of (3)
  double rotation_angle_rad = 0.0;          ///< largest attitude change from frame 0 (excitation)
};

class DynamicInitializer {
 public:
  struct Options {
    int min_frames = 5;  ///< poses (≥ 3 for an over-determined gravity)
    /// LiDAR-odometry pose noise per frame (1σ). Registration against a local map: ~1 cm, 0.1°.
    double position_sigma_m = 0.02;
    double rotation_sigma_rad = 0.2 * 3.14159265358979323846 / 180.0;
    /// Prior on the accelerometer bias (the simulator draws the MTi's turn-on bias with 0.02
    /// m/s² per axis). Where b_a is unobservable the tilt std becomes ≈ this / G (0.05 → 0.3°).
    double acc_bias_prior_sigma_mps2 = 0.05;
    /// b_a counts as observable when its largest posterior std is at most this.
    double max_acc_bias_std_mps2 = 0.03;
    bool require_acc_bias = false;  ///< an unobservable b_a gives kPoorlyConstrained
    /// Consistency limits (kInconsistent beyond them). They assume the two sigmas above match
    /// the odometry: residuals are judged relative to them.
    /// Attitude residual rms of (1) over rotation_sigma_rad, and √(whitened cost / dof) of (3).
    /// Measured on the simulator (1 cm / 0.1°, matched sigmas): 0.9 and 1.15; a 50 ms time offset
    /// gives 2.6 (attitude), a 1 m lever-arm error 2.3 (position).
    double max_normalized_rms = 2.0;
    /// | |g free| − G | beyond this plus 3σ of |g free| (weak gravity is kPoorlyConstrained).
    double max_gravity_norm_error_mps2 = 0.3;
    /// A larger gyro bias is taken for a time offset between poses and IMU (which the bias fit
    /// absorbs: 30 ms gave 0.018 rad/s on the slalom). MTi turn-on biases are ≤ 0.2 °/s.
    double max_gyro_bias_radps = 0.02;
    /// Constraint limits (kPoorlyConstrained beyond them).
    double max_gravity_tilt_std_rad = 0.02;  ///< ≈ 1.1°
    double max_velocity_std_mps = 0.1;
    int gyro_iterations = 3;     ///< of step (1), each with re-integration
    int gravity_iterations = 4;  ///< of step (3)
  };

  /// Takes the gravity magnitude (gravity_mps2) and the IMU noise model from the config.
  explicit DynamicInitializer(const EstimatorConfig& config);
  DynamicInitializer(const EstimatorConfig& config, const Options& options);

  /// Aligns the poses (time-ordered, ≥ min_frames) with the samples (time-ordered, spanning the
  /// first to the last pose) for the extrinsic T_imu_lidar. Stateless; safe to call repeatedly
  /// on a sliding set of poses until the status is kOk.
  DynamicInitResult Solve(std::span<const StampedLidarPose> poses,
                          std::span<const ImuSample> imu,
                          const Eigen::Isometry3d& T_imu_lidar) const;

  const Options& options() const { return options_; }

 private:
  double gravity_mps2_;
  ImuNoiseConfig noise_;
  Options options_;
};

}  // namespace swlio::estimator

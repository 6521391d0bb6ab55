#pragma once
/// @file
/// Tightly coupled sliding-window LiDAR-inertial estimator (issue 6; paper §4.3, eq. 17–21).
///
/// Frames sit at sweep ends. Each frame holds pose [p; q] (7, PoseManifold) and speed_bias
/// [v, b_a, b_g] (9); the extrinsic T_imu_lidar is one more block, constant unless
/// `estimate_extrinsic` (then tied to its configured value by a weak prior).
///
/// Per sweep (ARCHITECTURE.md, "tightly coupled sliding window"):
///  1. propagate the IMU from the newest optimized frame → de-skew → front end;
///  2. register the sweep alone from the IMU prediction (ScanMatcher::Match), associate its
///     features with the local map (VoxelMaps of keyframe features, world frame) there, and
///     linearize its point-to-plane / point-to-line factors (eq. 17–18, Huber, σ
///     `lidar_sigma_m`) into ≤ 6 rows (≤ 12 with the extrinsic): lidar_rows.h, with
///     degenerate directions left out and a covariance floor (`lidar_floor_sigma_*`);
///  3. one Ceres problem over the window, started from the IMU prediction: ImuFactor between
///     consecutive frames (eq. 21, pre-integrated covariance), every frame's LiDAR rows, the
///     marginalization prior (at start: a Gaussian prior on the first frame from the static
///     initialization, which also fixes the gauge) and a weak per-frame b_a prior; with
///     `estimate_gravity_tilt` the IMU factors also take the map's tilt against gravity
///     (gravity_tilt_imu_factor.h, one block kept by the marginalization); where the
///     solve moved the newest pose past the re-association thresholds, associate and
///     linearize again and re-solve (`reassociations`);
///  4. re-integrate IMU factors whose frame-i biases moved past
///     Preintegrator::NeedsReintegration; keyframe features into the maps at the optimized pose;
///  5. when the window holds more than `window_size` frames, marginalize the oldest
///     (Marginalizer: its LiDAR rows, its IMU factor and the previous prior).
/// A frame's LiDAR term is relinearized only while it is the newest (LIO-Mapping evaluates
/// every frame's point factors in every iteration, which is what made it slow).
/// Degeneracy: the 6×6 LiDAR Hessian of the newest frame (tangent [δp; δφ] of T_world_imu),
/// its eigenvalues and the number of directions left to the IMU are reported in every result.
/// Pure library: no clock (StageTimes through NowNsFn), no printing.

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "swlio/estimator/calibration/extrinsic_calibration_run.h"
#include "swlio/estimator/common/keyframe_cloud.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/init/dynamic_bootstrap.h"
#include "swlio/estimator/registration/lidar_odometry.h"
#include "swlio/estimator/window/divergence_monitor.h"
#include "swlio/estimator/window/marginalization.h"
#include "swlio/estimator/window/state_covariance.h"
#include "swlio/estimator/window/time_offset_estimator.h"
#include "swlio/estimator/window/window_estimator_config.h"

namespace swlio::estimator {

struct WindowResult {
  OdometryResult odometry;  ///< state of the newest frame, stage times, LiDAR Hessian in match
  size_t window_frames = 0;
  int solver_iterations = 0;  ///< summed over the solves of this sweep
  int prior_rank = 0;         ///< rows of the current marginalization prior
  size_t lidar_factors = 0;   ///< LiDAR point factors in the last solve (newest frame)
  /// Marginalizations so far that failed (the prior then restarts from the kept frame).
  size_t marginalization_failures = 0;
  /// Marginal covariance of the newest state (state_covariance.h) over the window, at the
  /// solution; `valid` false when not computed (`covariance` off, or rank-deficient).
  StateCovariance covariance;
  /// Tilt [θx, θy] (rad) of the map frame against gravity: Exp([θx, θy, 0]) rotates map
  /// vectors into the gravity-aligned frame (zero unless `estimate_gravity_tilt`).
  Eigen::Vector2d gravity_tilt_rad = Eigen::Vector2d::Zero();
  /// The sweep's registration moved the IMU prediction by this much (negative: not registered).
  double prediction_error_m = -1.0;
  double prediction_error_rad = -1.0;
  size_t reinitializations = 0;  ///< so far, including this sweep's
  /// Wheel odometry (WheelFactorConfig): frames so far with a velocity factor, and measurements
  /// the slip gate refused.
  size_t wheel_factors = 0;
  size_t wheel_rejected = 0;
  size_t standstill_frames = 0;  ///< frames so far that got a zero-velocity factor
  /// The LiDAR–IMU time offset applied to the IMU samples, its estimate and excitation
  /// (time_offset_estimator.h).
  TimeOffsetStatus time_offset;
  /// Local-map points this sweep's keyframe saw through and removed (visibility_image.h), and
  /// all so far.
  size_t dynamic_removed = 0;
  size_t dynamic_removed_total = 0;
  // The small fields together (no padding between them).
  /// Not kNone: this sweep's state was not believable (divergence_monitor.h), so the window
  /// re-initialized; the result is kInitializing and the state is not to be used.
  DivergenceReason diverged = DivergenceReason::kNone;
  /// The online extrinsic calibration finished with this sweep and the window restarted on it.
  bool extrinsic_calibrated = false;
  bool wheel_factor = false;  ///< the newest frame got a wheel velocity factor
  bool standstill = false;    ///< this sweep's frame got a zero-velocity factor
  /// This sweep became a keyframe of the local map: its features and pose (for loop closure
  /// and map saving); null otherwise.
  std::shared_ptr<const KeyframeCloud> keyframe;
};

class WindowEstimator {
 public:
  explicit WindowEstimator(const WindowEstimatorConfig& config, NowNsFn now_ns = nullptr);
  ~WindowEstimator();
  WindowEstimator(const WindowEstimator&) = delete;
  WindowEstimator& operator=(const WindowEstimator&) = delete;

  /// A sample as stamped; the window takes it at its stamp minus the estimated time offset
  /// (`time_offset`).
  void AddImu(const ImuSample& stamped);
  /// Chassis wheel odometry (time order; used when `wheel.enabled`).
  void AddWheel(const WheelOdometry& sample);
  WindowResult AddScan(const Scan& scan);

  /// Back to uninitialized with an empty map, as after a divergence (an operator's `swlioctl
  /// reset`): the next initialization (static or moving) is placed at the newest state that
  /// passed the divergence checks (position and yaw), so the world frame carries on. Counted in
  /// `reinitializations`.
  void Reset();

  bool initialized() const { return initialized_; }
  size_t window_frames() const { return frames_.size(); }
  /// Points in the local maps (planes and edges): bounded by their radius and voxel capacity.
  size_t map_points() const { return plane_map_.size() + edge_map_.size(); }
  /// The extrinsic in use: the configured one, or its online estimate (`estimate_extrinsic`).
  Eigen::Isometry3d T_imu_lidar() const { return PoseFromParameters(extrinsic_.data()); }
  /// The LiDAR–IMU time offset applied now (ns; > 0: a sample stamped s is taken at s − offset).
  /// A sweep ending at t is covered by the IMU once a sample stamped after t + offset arrived.
  int64_t imu_time_offset_ns() const { return time_offset_.offset_ns(); }
  /// The last sweep's points de-skewed into the LiDAR frame at its end (what the front end
  /// read); valid until the next AddScan.
  const Scan& deskewed() const { return deskewed_; }
  /// The online extrinsic calibration (calibrate_extrinsic_s): its result once applied, and
  /// while it runs, its attempts and the last reason it was refused (null when off or done).
  const ExtrinsicCalibration* calibration() const { return calibrated_.get(); }
  const ExtrinsicCalibrationRun* calibration_run() const { return calibration_.get(); }

 private:
  struct Frame;

  bool PropagateAndExtract(const Scan& scan, OdometryResult* result);
  std::unique_ptr<Frame> NewFrame(int64_t t_ns, const State& predicted);
  bool Preintegrate(const Frame& from, Frame* to);
  using LidarFactors = std::vector<std::unique_ptr<ceres::CostFunction>>;
  void Associate(Frame* frame);     ///< into planes_ / lines_
  void BuildFactors(Frame* frame);  ///< factors_ from planes_ / lines_
  /// Registers the frame alone (ScanMatcher) from its pose; true (pose set) when enough
  /// features matched.
  bool Prealign(Frame* frame);
  void SetInitialPrior(Frame* frame);
  /// The prior of a restart from a running frame (a failed marginalization, a calibration):
  /// SetInitialPrior with the configured gyro-bias σ. A standing start's σ (StaticGyroBiasSigma)
  /// is what the still window told of the bias then, not what the window knows of it now.
  void SetRestartPrior(Frame* frame);
  /// Roll/pitch σ of the diagonal first-frame prior (StaticStartTiltSigma after a standing
  /// start, unless estimate_gravity_tilt gives the ambiguity its own block).
  double DiagonalTiltSigma() const;
  Eigen::MatrixXd CorrelatedInitialPriorW(const Frame& frame) const;
  void StartFromBootstrap();
  State StateOf(const Frame& frame) const;
  /// True when the window is to estimate the time offset itself (window_prior_sigma_s): its
  /// IMU factors then share an offset block (time_offset_imu_factor.h) from the first
  /// estimate of the TimeOffsetEstimator beside it on (FreeOffset; until then the applied
  /// offset stands, as without the option).
  bool OffsetInWindow() const;
  /// True while the window's IMU factors follow the TimeOffsetEstimator's estimate
  /// (window_follows_estimate): the offset block then holds that estimate, constant in the
  /// solve, until FreeOffset makes it a parameter.
  bool FollowsOffset() const;
  /// The block set to the estimate, and the factors whose widening changed made again.
  void FollowOffset();
  /// σ a new IMU factor is widened by (time_shift_jacobian.h).
  double OffsetSigmaForFactors() const;
  /// The offset block starts at that estimate, with a prior of window_prior_sigma_s about it,
  /// and the window's IMU factors are made again with it.
  void FreeOffset();
  /// offset_prior_ about the block's value (a new start of prior_ holds nothing of it).
  void SetOffsetPrior();
  /// How Frame::MakeImu makes the IMU factors now (noise, gravity, tilt and offset blocks).
  struct FrameImuOptions;
  FrameImuOptions ImuFactorOptions() const;
  /// Frame's IMU factor (from `prev`) as the problem takes it, with its parameter blocks (the
  /// gravity tilt block and the time-offset block as configured).
  std::pair<ceres::CostFunction*, std::vector<double*>> ImuTerm(Frame& prev, Frame& frame);
  static ceres::Problem::Options ProblemOptions();
  /// The window's blocks and residuals (extrinsic, frames, IMU, LiDAR rows, priors).
  void BuildProblem(ceres::Problem& problem);
  int Solve(WindowResult* result);
  StateCovariance NewestCovariance();
  void Reintegrate();
  void Marginalize();
  /// Robust Gauss–Newton system of one frame's LiDAR factors over [pose; extrinsic] tangents.
  struct LidarSystem {
    Eigen::Matrix<double, 12, 12> H = Eigen::Matrix<double, 12, 12>::Zero();
    Eigen::Matrix<double, 12, 1> b = Eigen::Matrix<double, 12, 1>::Zero();
    double cost = 0.0;
  };
  LidarSystem LinearizeLidar(const Frame& frame, const LidarFactors& factors) const;
  void FillLidarHessian(const Frame& frame, const LidarSystem& lidar, MatchResult* match) const;
  /// Replaces the frame's LiDAR rows; returns the number of degenerate directions left out.
  int CompressLidar(const LidarSystem& lidar, Frame* frame) const;
  Eigen::MatrixXd LidarFloor(const Frame& frame, int n) const;
  /// Associates the frame at its pose and linearizes its LiDAR factors there.
  void Relinearize(Frame* frame, MatchResult* match, int* degenerate);
  bool MovedFromLinearization(const Frame& frame) const;
  std::vector<double*> LidarBlocks(Frame* frame);
  bool IsKeyframe(const Eigen::Isometry3d& T_world_lidar) const;
  /// The keyframe's features into the maps, after its sweep's free space took the moving
  /// objects out of them; returns its visibility image (null when off) and counts the removed.
  std::shared_ptr<const VisibilityImage> InsertFeatures(const Frame& frame, size_t* removed);
  /// Map points `image` sees through (visibility_image.h) out of both maps; returns how many.
  size_t RemoveSeenThrough(const VisibilityImage& image);
  /// The frame's wheel velocity factor from the samples around its time (window_wheel.cpp);
  /// true when it got one.
  bool AttachWheel(Frame* frame);
  /// The frame's zero-velocity factor when its IMU interval shows rest and the sweep's own
  /// registration `p_registered` agrees (window_standstill.cpp); true when it got one.
  bool AttachStandstill(Frame* frame, const Eigen::Vector3d& p_registered);
  /// Gyro rate at `t_ns` from the buffered IMU samples (the nearest one).
  Eigen::Vector3d GyroAt(int64_t t_ns) const;
  /// Restarts the window on a calibrated extrinsic (see calibrate_extrinsic_s): the newest
  /// frame is kept with a fresh prior, the maps are the calibration odometry's carried into the
  /// window's world at the newest sweep. False (nothing changed) when the odometry did not
  /// register the newest sweep.
  bool ApplyCalibration(const ExtrinsicCalibration& calibration);
  void ResetExtrinsicPrior();  ///< weak prior about the current extrinsic
  /// Checks the newest frame (divergence_monitor.h); kNone, or the window re-initialized.
  DivergenceReason CheckDivergence(const WindowResult& out);
  /// Back to uninitialized with an empty map; the next initialization (static or moving) is
  /// placed at the last believable pose (position and yaw) so the world frame carries on.
  void Reinitialize();
  /// The rigid yaw + translation that puts the new initialization's pose `T_new_imu` (at
  /// `t_ns`) where the last believable state says the robot was then: its position moved on at
  /// its velocity when `extrapolate` (a moving start), its yaw. Identity when there is no such
  /// state, or no re-initialization is pending.
  Eigen::Isometry3d AnchorFor(const Eigen::Isometry3d& T_new_imu,
                              int64_t t_ns,
                              bool extrapolate) const;
  void InsertKeyframe(const Eigen::Isometry3d& T_world_lidar,
                      const std::vector<Eigen::Vector3d>& planes_lidar,
                      const std::vector<Eigen::Vector3d>& edges_lidar);

  // 16-byte aligned members first (padding).
  Eigen::Isometry3d T_world_last_keyframe_ = Eigen::Isometry3d::Identity();
  WindowEstimatorConfig config_;
  NowNsFn now_ns_;
  StaticInitializer initializer_;
  DynamicBootstrap bootstrap_;
  double init_sigma_velocity_mps_, init_sigma_tilt_rad_, init_sigma_bias_acc_mps2_;
  Eigen::Vector3d init_sigma_bias_gyro_radps_;  ///< per axis (StaticGyroBiasSigma)
  State init_state_;
  /// Re-initialized: the next initialization is placed at this state (AnchorFor).
  std::optional<State> anchor_;
  ImuPropagator propagator_;
  TimeOffsetEstimator time_offset_;  ///< shifts the IMU samples by the estimated offset
  /// Tracked states that passed the checks, the last kGoodHistoryNs of them: a divergence may
  /// have begun a few sweeps before a check tripped, so the anchor is the oldest.
  std::deque<State> good_;
  std::deque<ImuSample> imu_;         ///< samples from just before the newest frame on
  std::deque<ImuSample> recent_imu_;  ///< the last standstill.imu_window_s (and a little more)
  ImuNoiseAdapter noise_adapter_;     ///< the IMU factors' noise, measured
  std::deque<WheelOdometry> wheel_;   ///< the last second of wheel odometry
  size_t wheel_factors_ = 0, wheel_rejected_ = 0;
  size_t standstill_frames_ = 0;
  size_t dynamic_removed_ = 0;
  FrontEnd front_end_;
  FrontEndOutput features_;
  Scan deskewed_;                        ///< the sweep being processed, de-skewed (reused)
  std::vector<ImuSample> imu_interval_;  ///< Preintegrate's samples (reused)
  VoxelMap plane_map_;
  VoxelMap edge_map_;
  ScanMatcher matcher_;
  PoseManifold manifold_;
  ceres::HuberLoss huber_;
  std::vector<double> extrinsic_;        ///< T_imu_lidar block (7)
  std::vector<double> gravity_tilt_;     ///< map tilt against gravity (gravity_tilt_imu_factor.h)
  std::vector<double> window_offset_s_;  ///< the IMU factors' time offset (OffsetInWindow)
  /// Its prior until a marginalization folds it into prior_; null otherwise.
  std::unique_ptr<MarginalizationPrior> offset_prior_;
  std::unique_ptr<MarginalizationPrior> extrinsic_prior_;
  std::unique_ptr<ExtrinsicCalibrationRun> calibration_;  ///< null when off or done
  std::unique_ptr<ExtrinsicCalibration> calibrated_;      ///< null until applied
  std::vector<double> zero_speed_bias_;
  LidarFactors factors_;                     ///< the newest frame's, reused
  std::vector<PlaneCorrespondence> planes_;  ///< the newest frame's correspondences
  std::vector<LineCorrespondence> lines_;
  std::unique_ptr<MarginalizationPrior> bias_prior_;  ///< null when disabled
  std::deque<std::unique_ptr<Frame>> frames_;  ///< oldest first; blocks stay at fixed addresses
  MarginalizationResult prior_;
  size_t marginalization_failures_ = 0;
  DivergenceMonitor divergence_;
  size_t reinitializations_ = 0;
  // Flags last (padding).
  bool initialized_ = false;
  bool have_keyframe_ = false;
  bool started_static_ = false;  ///< the last initialization was a standing start
  bool offset_free_ = false;     ///< window_offset_s_ is a parameter (FreeOffset)
};

}  // namespace swlio::estimator

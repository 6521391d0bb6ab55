#include "swlio/estimator/window/window_estimator.h"

#include <ceres/manifold.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>

#include "swlio/core/time.h"
#include "swlio/estimator/frontend/deskew.h"
#include "swlio/estimator/init/initial_prior.h"
#include "window_frame.h"

namespace swlio::estimator {

namespace {

void ToVectors(const std::vector<FeaturePoint>& in, std::vector<Eigen::Vector3d>* out) {
  out->clear();
  for (const FeaturePoint& f : in) out->push_back(f.xyz_m.cast<double>());
}

struct PriorBlock {
  const double* values;
  const ceres::Manifold* manifold;  ///< nullptr: Euclidean of `size`
  int size = kSpeedBiasSize;
};
using PriorBlocks = std::vector<PriorBlock>;

/// Gaussian prior r = W (x ⊟ x₀) on one or two blocks, as a MarginalizationPrior (J₀ = W).
std::unique_ptr<MarginalizationPrior> GaussianPrior(const PriorBlocks& blocks,
                                                    const Eigen::MatrixXd& W) {
  std::vector<MarginalizationPrior::Block> b;
  int offset = 0;
  for (const auto& [values, manifold, size] : blocks) {
    const int ambient = manifold != nullptr ? manifold->AmbientSize() : size;
    const int tangent = manifold != nullptr ? manifold->TangentSize() : size;
    b.push_back({manifold, Eigen::Map<const Eigen::VectorXd>(values, ambient), tangent, offset});
    offset += tangent;
  }
  return std::make_unique<MarginalizationPrior>(std::move(b), W, Eigen::VectorXd::Zero(W.rows()));
}

std::unique_ptr<MarginalizationPrior> DiagonalPrior(const PriorBlocks& blocks,
                                                    const Eigen::VectorXd& sigmas) {
  return GaussianPrior(blocks, sigmas.cwiseInverse().asDiagonal());
}

/// The state with its world-frame quantities rotated by Q (map ↔ gravity-aligned frame).
State Rotated(State s, const Eigen::Quaterniond& Q) {
  s.T_world_imu = Eigen::Isometry3d(Q) * s.T_world_imu;
  s.vel_world = Q * s.vel_world;
  return s;
}

ImuSample At(ImuSample s, int64_t t_ns) {
  s.t_ns = t_ns;
  return s;
}

/// The first frame's gyro-bias σ after a standing start: the static initializer's standard error
/// of the mean rate, per axis (about 2e-4 rad/s for the MTi-G-710 over 1 s), never below what
/// the datasheet's white noise allows a plain mean over that window (density/√T: 1.7e-4 rad/s)
/// nor below 1e-5 rad/s (a fifth of its 10 °/h in-run bias stability). The configured
/// 0.005 rad/s, 30 times looser, let the LiDAR's yaw jitter move the bias while the robot still
/// stood: on `short` seeds 1–3 the z bias was 0.7–1.7e-4 rad/s off after the initialization,
/// 1.7–2.0e-4 off three seconds later (seed 2: 7.7e-4 within the first second), and the yaw
/// drifted with it (docs/notes/2026-11-25-tightly-coupled-yaw-gyro-bias.md, "The gyro bias
/// after a standing start").
Eigen::Vector3d StaticGyroBiasSigma(const StaticInitResult& init, const ImuNoiseConfig& noise) {
  constexpr double kFloorRadps = 1e-5;
  const double white_radps =
      init.window_s > 0.0 ? noise.gyro_noise_density_radps_per_sqrthz / std::sqrt(init.window_s)
                          : 0.0;
  return init.bias_gyro_std.cwiseMax(std::max(kFloorRadps, white_radps));
}

}  // namespace

double StaticStartTiltSigma(const WindowEstimatorConfig& config) {
  return std::max(config.init_sigma_rotation_rad,
                  config.init_sigma_bias_acc_mps2 / config.odometry.estimator.gravity_mps2);
}

namespace {

DynamicBootstrapConfig BootstrapConfig(const WindowEstimatorConfig& config) {
  DynamicBootstrapConfig c = config.bootstrap;
  c.odometry = config.odometry;
  return c;
}

}  // namespace

WindowEstimator::WindowEstimator(const WindowEstimatorConfig& config, NowNsFn now_ns)
    : config_(WithWindowFeatures(config)),
      now_ns_(now_ns),
      initializer_(config_.odometry.estimator),
      bootstrap_(BootstrapConfig(config_)),
      init_sigma_velocity_mps_(config_.init_sigma_velocity_mps),
      init_sigma_tilt_rad_(config_.init_sigma_rotation_rad),
      init_sigma_bias_acc_mps2_(config_.init_sigma_bias_acc_mps2),
      init_sigma_bias_gyro_radps_(Eigen::Vector3d::Constant(config_.init_sigma_bias_gyro_radps)),
      propagator_(config_.odometry.estimator.gravity_mps2),
      time_offset_(config_.time_offset),
      noise_adapter_(config_.odometry.estimator.imu_noise, config_.imu_noise_adapter),
      front_end_(config_.odometry.front_end),
      plane_map_(config_.odometry.plane_map),
      edge_map_(config_.odometry.edge_map),
      matcher_(config_.odometry.matcher),
      huber_(config_.huber_m / config_.lidar_sigma_m),
      extrinsic_(kPoseSize),
      gravity_tilt_(kGravityTiltSize, 0.0),
      window_offset_s_(1, config_.time_offset.initial_offset_s),
      divergence_(config_.divergence) {
  PoseToParameters(config_.odometry.T_imu_lidar, extrinsic_.data());
  ResetExtrinsicPrior();
  if (config_.calibrate_extrinsic_s > 0.0) {
    // The LiDAR-only odometry beside the window, with the LiDAR-only mode's own features.
    calibration_ = std::make_unique<ExtrinsicCalibrationRun>(
        config.odometry, config_.calibrate_extrinsic_s, config_.calibrate_retry_s);
  }
  if (config_.bias_prior_sigma_acc_mps2 > 0.0 || config_.bias_prior_sigma_gyro_radps > 0.0) {
    auto sigma_or_none = [](double sigma) { return sigma > 0.0 ? sigma : 1e3; };
    zero_speed_bias_.assign(kSpeedBiasSize, 0.0);
    Eigen::VectorXd sb_sigmas(kSpeedBiasSize);
    sb_sigmas << Eigen::Vector3d::Constant(1e3),  // velocity: no information
        Eigen::Vector3d::Constant(sigma_or_none(config_.bias_prior_sigma_acc_mps2)),
        Eigen::Vector3d::Constant(sigma_or_none(config_.bias_prior_sigma_gyro_radps));
    bias_prior_ = DiagonalPrior({{zero_speed_bias_.data(), nullptr}}, sb_sigmas);
  }
}

WindowEstimator::~WindowEstimator() = default;

void WindowEstimator::ResetExtrinsicPrior() {
  Eigen::VectorXd sigmas(kPoseTangentSize);
  sigmas << Eigen::Vector3d::Constant(config_.extrinsic_prior_sigma_m),
      Eigen::Vector3d::Constant(config_.extrinsic_prior_sigma_rad);
  extrinsic_prior_ = DiagonalPrior({{extrinsic_.data(), &manifold_}}, sigmas);
}

void WindowEstimator::AddImu(const ImuSample& stamped) {
  time_offset_.AddImu(stamped);
  const ImuSample sample = time_offset_.Shifted(stamped);
  if (calibration_) calibration_->AddImu(sample);
  noise_adapter_.Add(sample);
  if (!recent_imu_.empty() && sample.t_ns < recent_imu_.back().t_ns) recent_imu_.clear();
  recent_imu_.push_back(sample);
  const int64_t keep_ns = SecToNs(config_.standstill.imu_window_s) + kNsPerSec / 5;
  while (!recent_imu_.empty() && recent_imu_.front().t_ns < sample.t_ns - keep_ns) {
    recent_imu_.pop_front();
  }
  if (initialized_) {
    imu_.push_back(sample);
    return;
  }
  // Constant velocity feels like standing still to an IMU: with the moving start enabled, a
  // static result is refused while the LiDAR registers motion (measured: `aggressive` entered
  // at 20 s, 1.5 m/s, initialized "at rest", the velocity took 1 s to converge). Without a
  // registration (too few features) the IMU's judgement stands.
  const double speed_mps = bootstrap_.registered_speed_mps();
  const bool lidar_agrees =
      !config_.dynamic_init || speed_mps < 0.0 || speed_mps < config_.static_max_speed_mps;
  if (initializer_.Add(sample).status == InitStatus::kInitialized && lidar_agrees) {
    initialized_ = true;
    init_state_ = initializer_.result().state;
    const Eigen::Isometry3d T_fix = AnchorFor(init_state_.T_world_imu, init_state_.t_ns, false);
    init_state_.T_world_imu = T_fix * init_state_.T_world_imu;
    started_static_ = true;
    init_sigma_bias_gyro_radps_ =
        StaticGyroBiasSigma(initializer_.result(), config_.odometry.estimator.imu_noise);
    anchor_.reset();
    imu_.assign(1, sample);
    bootstrap_.Reset();
    return;
  }
  if (!config_.dynamic_init) return;
  bootstrap_.AddImu(sample);
  // Kept for the first IMU factor after a moving start (a second is plenty).
  imu_.push_back(sample);
  while (!imu_.empty() && imu_.front().t_ns < sample.t_ns - kNsPerSec) imu_.pop_front();
}

void WindowEstimator::StartFromBootstrap() {
  const BootstrapResult& r = bootstrap_.result();
  initialized_ = true;
  started_static_ = false;  // the alignment's tilt σ already holds what it could not observe
  init_state_ = r.state;
  // Anchored where the new world starts: the alignment window's oldest sweep.
  const std::vector<BootstrapKeyframe>& kfs = bootstrap_.keyframes();
  const Eigen::Isometry3d T_fix =
      kfs.empty()
          ? AnchorFor(r.state.T_world_imu, r.state.t_ns, true)
          : AnchorFor(kfs.front().T_world_lidar * T_imu_lidar().inverse(), kfs.front().t_ns, true);
  init_state_.T_world_imu = T_fix * r.state.T_world_imu;
  init_state_.vel_world = T_fix.linear() * r.state.vel_world;
  anchor_.reset();
  // The first frame's prior from the alignment's own uncertainty (never tighter than the
  // configured static one).
  init_sigma_velocity_mps_ = std::max(config_.init_sigma_velocity_mps, r.velocity_std_mps);
  init_sigma_tilt_rad_ = std::max(config_.init_sigma_rotation_rad, r.gravity_tilt_std_rad);
  init_sigma_bias_acc_mps2_ = std::max(config_.init_sigma_bias_acc_mps2, r.bias_acc_std.maxCoeff());
  init_sigma_bias_gyro_radps_.setConstant(config_.init_sigma_bias_gyro_radps);
  for (const BootstrapKeyframe& kf : kfs) {
    InsertKeyframe(T_fix * kf.T_world_lidar, kf.planes_lidar, kf.edges_lidar);
  }
  while (imu_.size() > 1 && imu_[1].t_ns <= init_state_.t_ns) imu_.pop_front();
}

State WindowEstimator::StateOf(const Frame& f) const {
  State s;
  s.t_ns = f.t_ns;
  s.T_world_imu = PoseFromParameters(f.pose.data());
  s.vel_world = Eigen::Map<const Eigen::Vector3d>(&f.speed_bias[kSbVel]);
  s.bias_acc = f.BiasAcc();
  s.bias_gyro = f.BiasGyro();
  return s;
}

bool WindowEstimator::PropagateAndExtract(const Scan& scan, OdometryResult* result) {
  // The propagator's gravity is the map's −z: integrate in the gravity-aligned frame (Q).
  const Eigen::Quaterniond Q = GravityTiltRotation(gravity_tilt_.data());
  propagator_.Reset(Rotated(frames_.empty() ? init_state_ : StateOf(*frames_.back()), Q));
  for (const ImuSample& s : imu_) {
    if (s.t_ns > scan.t_end_ns) break;
    propagator_.Add(s);
  }
  propagator_.ExtrapolateTo(scan.t_end_ns);
  const DeskewResult deskew = DeskewScan(scan, propagator_.track(), T_imu_lidar(), &deskewed_);
  result->points_uncovered = deskew.uncovered;
  front_end_.Process(deskewed_, &features_);
  return true;
}

std::unique_ptr<WindowEstimator::Frame> WindowEstimator::NewFrame(int64_t t_ns,
                                                                  const State& predicted) {
  auto f = std::make_unique<Frame>();
  f->t_ns = t_ns;
  PoseToParameters(predicted.T_world_imu, f->pose.data());
  Eigen::Map<Eigen::Vector3d>(&f->speed_bias[kSbVel]) = predicted.vel_world;
  Eigen::Map<Eigen::Vector3d>(&f->speed_bias[kSbBiasAcc]) = predicted.bias_acc;
  Eigen::Map<Eigen::Vector3d>(&f->speed_bias[kSbBiasGyro]) = predicted.bias_gyro;
  ToVectors(features_.features.planes, &f->planes_lidar);
  ToVectors(features_.features.edges, &f->edges_lidar);
  return f;
}

bool WindowEstimator::Preintegrate(const Frame& from, Frame* to) {
  // The samples over [from, to]: the last one before `from` (else the first one, held back to
  // `from`), those in between, the first at or after `to` (else the last one, held) and the one
  // after it where it has come (the line of the cut step's part, preintegration.h).
  std::vector<ImuSample>& s = imu_interval_;  // reused: no allocation per sweep
  s.clear();
  bool past_end = false;
  for (const ImuSample& x : imu_) {
    if (x.t_ns < from.t_ns) {
      s.assign(1, x);
      continue;
    }
    if (s.empty() && x.t_ns > from.t_ns) s.push_back(At(x, from.t_ns));
    s.push_back(x);
    if (past_end) break;
    past_end = x.t_ns >= to->t_ns;
  }
  if (s.empty()) return false;
  if (s.back().t_ns < to->t_ns) s.push_back(At(s.back(), to->t_ns));  // hold the last rates
  const ImuNoiseConfig noise = noise_adapter_.Effective();
  to->pre = std::make_unique<Preintegrator>(noise, from.BiasGyro(), from.BiasAcc());
  if (to->pre->Integrate(s, from.t_ns, to->t_ns) != PreintegrationStatus::kOk) return false;
  to->pre_applied_offset_s = NsToSec(time_offset_.offset_ns());
  to->pre_offset_sigma_s = OffsetSigmaForFactors();
  // J only where the offset's uncertainty widens this factor or the window moves or estimates it.
  to->pre_time_shift_jacobian =
      to->pre_offset_sigma_s > 0.0 || OffsetInWindow() || FollowsOffset()
          ? TimeShiftJacobian(to->pre->result(), EndRates(s, from.t_ns), EndRates(s, to->t_ns))
          : Vec9::Zero();
  to->MakeImu(ImuFactorOptions());
  return to->imu != nullptr;
}

void WindowEstimator::SetInitialPrior(Frame* f) {
  prior_ = MarginalizationResult{};
  PriorBlocks blocks = {{f->pose.data(), &manifold_}, {f->speed_bias.data(), nullptr}};
  const int n = kPoseTangentSize + kSpeedBiasSize;
  const int n_tilt = config_.estimate_gravity_tilt ? kGravityTiltSize : 0;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n + n_tilt, n + n_tilt);
  if (config_.init_tilt_follows_bias) {
    W.topLeftCorner(n, n) = CorrelatedInitialPriorW(*f);
  } else {
    Eigen::VectorXd sigmas(kPoseTangentSize + kSpeedBiasSize);
    sigmas << Eigen::Vector3d::Constant(config_.init_sigma_position_m),
        Eigen::Vector3d(DiagonalTiltSigma(), DiagonalTiltSigma(), config_.init_sigma_rotation_rad),
        Eigen::Vector3d::Constant(init_sigma_velocity_mps_),
        Eigen::Vector3d::Constant(init_sigma_bias_acc_mps2_), init_sigma_bias_gyro_radps_;
    W.topLeftCorner(n, n) = sigmas.cwiseInverse().asDiagonal();
  }
  prior_.kept_blocks = {f->pose.data(), f->speed_bias.data()};
  if (config_.estimate_gravity_tilt) {
    // A standing start cannot tell the horizontal accelerometer bias from tilt.
    const double sigma_tilt_rad =
        init_sigma_bias_acc_mps2_ / config_.odometry.estimator.gravity_mps2;
    W.bottomRightCorner(n_tilt, n_tilt) =
        Eigen::MatrixXd::Identity(n_tilt, n_tilt) / sigma_tilt_rad;
    blocks.push_back({gravity_tilt_.data(), nullptr, kGravityTiltSize});
    prior_.kept_blocks.push_back(gravity_tilt_.data());
  }
  prior_.prior = GaussianPrior(blocks, W);
  prior_.rank = n + n_tilt;
  if (offset_free_) SetOffsetPrior();
}

void WindowEstimator::SetRestartPrior(Frame* f) {
  init_sigma_bias_gyro_radps_.setConstant(config_.init_sigma_bias_gyro_radps);
  SetInitialPrior(f);
}

double WindowEstimator::DiagonalTiltSigma() const {
  // With the map's tilt estimated, that block carries the ambiguity (SetInitialPrior) and the
  // first frame's tilt is the map's gauge.
  const bool ambiguous = started_static_ && !config_.estimate_gravity_tilt;
  return ambiguous ? StaticStartTiltSigma(config_) : init_sigma_tilt_rad_;
}

Eigen::MatrixXd WindowEstimator::CorrelatedInitialPriorW(const Frame& f) const {
  // Tilt and accelerometer bias correlated as the initialization left them (initial_prior.h).
  InitialStdDevs sigma;
  sigma.position_m = config_.init_sigma_position_m;
  sigma.yaw_rad = config_.init_sigma_rotation_rad;
  sigma.tilt_measured_rad = init_sigma_tilt_rad_;
  sigma.velocity_mps = init_sigma_velocity_mps_;
  sigma.bias_acc_mps2 = init_sigma_bias_acc_mps2_;
  sigma.bias_gyro_radps = init_sigma_bias_gyro_radps_.maxCoeff();  // one σ for the three axes
  const Eigen::MatrixXd Sigma = InitialCovariance(PoseFromParameters(f.pose.data()).linear(),
                                                  config_.odometry.estimator.gravity_mps2, sigma);
  return Sigma.llt().matrixL().solve(Eigen::MatrixXd::Identity(Sigma.rows(), Sigma.cols()));
}

WindowResult WindowEstimator::AddScan(const Scan& scan) {
  StageTimer timer(now_ns_);
  WindowResult out;
  out.reinitializations = reinitializations_;  // also on the results while re-initializing
  OdometryResult& result = out.odometry;
  result.points_in = scan.points.size();
  if (calibration_) calibration_->AddScan(scan);
  const int64_t t_last = frames_.empty() ? init_state_.t_ns : frames_.back()->t_ns;
  if (!initialized_) {
    // A moving start: LiDAR-only registration aligned to the IMU (dynamic_bootstrap.h).
    if (config_.dynamic_init && bootstrap_.AddScan(scan) == BootstrapStatus::kReady) {
      StartFromBootstrap();
    }
    return out;
  }
  if (scan.t_start_ns < t_last) {  // out of order or overlapping: not used
    result.status = OdometryStatus::kSkipped;
    return out;
  }

  PropagateAndExtract(scan, &result);
  const Eigen::Quaterniond Q = GravityTiltRotation(gravity_tilt_.data());
  std::unique_ptr<Frame> frame = NewFrame(scan.t_end_ns, Rotated(propagator_.state(), Q.inverse()));
  result.planes = frame->planes_lidar.size();
  result.edges = frame->edges_lidar.size();
  result.times.frontend_ms = timer.Lap();

  if (frames_.empty())
    SetInitialPrior(frame.get());
  else
    Preintegrate(*frames_.back(), frame.get());  // without it: LiDAR and prior only
  out.wheel_factor = config_.wheel.enabled && AttachWheel(frame.get());
  int degenerate = 0;
  const bool have_map = plane_map_.size() > 0;
  std::optional<Eigen::Vector3d> registered;  ///< the sweep's own registration, if any
  if (have_map) {
    // The LiDAR rows are linearized at the scan's own registration (from the IMU prediction);
    // the window solve then starts again from the prediction, which agrees with the IMU
    // factor: starting from the registered pose put a 10⁸ cost on that factor, which the
    // solver did not work off in its iterations.
    const std::array<double, kPoseSize> predicted = frame->pose;
    if (config_.prealign && Prealign(frame.get())) {
      registered = PoseFromParameters(frame->pose.data()).translation();
      time_offset_.AddRegistration(
          scan.t_end_ns, Eigen::Quaterniond(PoseFromParameters(frame->pose.data()).linear()));
      const Eigen::Isometry3d d =
          PoseFromParameters(predicted.data()).inverse() * PoseFromParameters(frame->pose.data());
      out.prediction_error_m = d.translation().norm();
      out.prediction_error_rad = Eigen::AngleAxisd(d.linear()).angle();
    }
    Relinearize(frame.get(), &result.match, &degenerate);
    frame->pose = predicted;
  }
  if (registered) out.standstill = AttachStandstill(frame.get(), *registered);
  result.times.match_ms = timer.Lap();
  frames_.push_back(std::move(frame));
  if (OffsetInWindow() && !offset_free_ && time_offset_.status().updates > 0) FreeOffset();
  FollowOffset();
  while (imu_.size() > 1 && imu_[1].t_ns <= scan.t_end_ns) imu_.pop_front();

  Frame& newest = *frames_.back();
  if (frames_.size() > 1) {
    out.solver_iterations += Solve(&out);
    // The LiDAR rows are exact to second order near their linearization: associate again
    // only where the window solve moved the newest pose (ScanMatcher's rule).
    for (int i = 0; i < config_.reassociations && have_map && MovedFromLinearization(newest); ++i) {
      result.times.optimize_ms += timer.Lap();
      Relinearize(&newest, &result.match, &degenerate);
      result.times.match_ms += timer.Lap();
      out.solver_iterations += Solve(&out);
    }
    Reintegrate();
  }
  if (config_.covariance) out.covariance = NewestCovariance();
  result.status = OdometryStatus::kTracking;
  if (have_map && newest.plane_factors + newest.line_factors < config_.odometry.min_inliers) {
    result.status = OdometryStatus::kMatchFailed;  // the IMU carries this frame
  }
  out.diverged = CheckDivergence(out);
  out.reinitializations = reinitializations_;  // counting this sweep's
  if (out.diverged != DivergenceReason::kNone) {
    const StageTimes times = result.times;
    result = OdometryResult{};  // kInitializing: nothing of this sweep is to be used
    result.times = times;
    result.times.optimize_ms += timer.Lap();
    result.times.total_ms =
        result.times.frontend_ms + result.times.match_ms + result.times.optimize_ms;
    return out;
  }
  const Eigen::Isometry3d T_world_lidar = PoseFromParameters(newest.pose.data()) * T_imu_lidar();
  result.keyframe = IsKeyframe(T_world_lidar);
  if (result.keyframe) {
    result.times.optimize_ms += timer.Lap();
    std::shared_ptr<const VisibilityImage> image = InsertFeatures(newest, &out.dynamic_removed);
    dynamic_removed_ += out.dynamic_removed;
    out.keyframe = std::make_shared<const KeyframeCloud>(
        KeyframeCloud{newest.t_ns, PoseFromParameters(newest.pose.data()), T_imu_lidar(),
                      newest.planes_lidar, newest.edges_lidar, std::move(image)});
    result.times.map_ms = timer.Lap();
  }
  out.dynamic_removed_total = dynamic_removed_;
  result.state = StateOf(newest);
  result.match.T_world_lidar = T_world_lidar;
  result.match.iterations = out.solver_iterations;
  result.match.degenerate_directions = degenerate;
  if (frames_.size() > config_.window_size) Marginalize();
  if (calibration_) {
    if (const auto c = calibration_->TryCalibrate(); c && ApplyCalibration(*c)) {
      out.extrinsic_calibrated = true;
      calibrated_ = std::make_unique<ExtrinsicCalibration>(*c);
      calibration_.reset();
    }
  }
  out.window_frames = frames_.size();
  out.prior_rank = prior_.rank;
  out.marginalization_failures = marginalization_failures_;
  out.gravity_tilt_rad = Eigen::Vector2d(gravity_tilt_[0], gravity_tilt_[1]);
  out.wheel_factors = wheel_factors_;
  out.wheel_rejected = wheel_rejected_;
  out.standstill_frames = standstill_frames_;
  out.time_offset = time_offset_.status();
  if (offset_free_) out.time_offset.window_offset_s = window_offset_s_[0];
  result.times.optimize_ms += timer.Lap();
  result.times.total_ms = result.times.frontend_ms + result.times.match_ms +
                          result.times.optimize_ms + result.times.map_ms;
  return out;
}

}  // namespace swlio::estimator

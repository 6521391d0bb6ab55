// The batch LiDAR–IMU extrinsic calibration (extrinsic_calibrator.h). The LiDAR pose and prior
// residuals are small templated functors under Ceres autodiff (this file's only autodiff); the
// IMU residual is the window's analytic ImuFactor.

#include "swlio/estimator/calibration/extrinsic_calibrator.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/covariance.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/rotation.h>
#include <ceres/solver.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {
namespace {

constexpr size_t kAlignmentPoses = 30;
constexpr size_t kMaxCorrelationLag = 20;  ///< poses (2 s at 10 Hz)

using Pose = std::array<double, kPoseSize>;
using SpeedBias = std::array<double, kSpeedBiasSize>;

/// Log(R_aᵀ R_b) for unit quaternions given as Eigen quaternions (w last in storage).
template <typename T>
void RelativeRotationVector(const Eigen::Quaternion<T>& q_a,
                            const Eigen::Quaternion<T>& q_b,
                            T* phi) {
  const Eigen::Quaternion<T> d = q_a.conjugate() * q_b;
  const T wxyz[4] = {d.w(), d.x(), d.y(), d.z()};
  ceres::QuaternionToAngleAxis(wxyz, phi);
}

/// The LiDAR pose measured by the odometry against the IMU pose and the extrinsic, as the
/// error in the measured pose's tangent (the registration's [ρ; φ], scan_matcher.h):
/// δ = [R_measᵀ (p_est − p_meas); Log(R_measᵀ R_est)], whitened by U (Uᵀ U = information).
struct LidarPoseResidual {
  Eigen::Quaterniond q_world0_lidar;  ///< T̄_world_w0 · T_w0_lidar, before the tilt
  Eigen::Vector3d p_world0_lidar;
  Eigen::Matrix<double, 6, 6> sqrt_information;

  template <typename T>
  bool operator()(const T* pose, const T* extrinsic, const T* tilt, T* r) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_wi(pose), t_il(extrinsic);
    const Eigen::Quaternion<T> q_wi = Eigen::Map<const Eigen::Quaternion<T>>(pose + 3).normalized();
    const Eigen::Quaternion<T> q_il =
        Eigen::Map<const Eigen::Quaternion<T>>(extrinsic + 3).normalized();
    const T aa[3] = {tilt[0], tilt[1], T(0)};
    T q_tilt_wxyz[4];
    ceres::AngleAxisToQuaternion(aa, q_tilt_wxyz);
    const Eigen::Quaternion<T> q_tilt(q_tilt_wxyz[0], q_tilt_wxyz[1], q_tilt_wxyz[2],
                                      q_tilt_wxyz[3]);
    const Eigen::Quaternion<T> q_meas = q_tilt * q_world0_lidar.cast<T>();
    const Eigen::Matrix<T, 3, 1> p_meas = q_tilt * p_world0_lidar.cast<T>();
    const Eigen::Quaternion<T> q_est = q_wi * q_il;
    const Eigen::Matrix<T, 3, 1> p_est = q_wi * t_il + p_wi;
    Eigen::Matrix<T, 6, 1> delta;
    delta.template head<3>() = q_meas.conjugate() * (p_est - p_meas);
    RelativeRotationVector(q_meas, q_est, delta.data() + 3);
    Eigen::Map<Eigen::Matrix<T, 6, 1>> whitened(r);
    whitened = sqrt_information.cast<T>() * delta;
    return true;
  }
};

/// A pose block about a fixed pose: [Δp / σ_p; Log(R̄ᵀ R) / σ_r].
struct PosePriorResidual {
  Eigen::Quaterniond q_prior;
  Eigen::Vector3d p_prior;
  double w_position, w_rotation;

  template <typename T>
  bool operator()(const T* pose, T* r) const {
    const Eigen::Quaternion<T> q = Eigen::Map<const Eigen::Quaternion<T>>(pose + 3).normalized();
    for (int i = 0; i < 3; ++i) r[i] = T(w_position) * (pose[i] - T(p_prior[i]));
    RelativeRotationVector(q_prior.cast<T>(), q, r + 3);
    for (int i = 3; i < 6; ++i) r[i] *= T(w_rotation);
    return true;
  }
};

/// The accelerometer bias of a speed-bias block about zero.
struct AccBiasPriorResidual {
  double weight;
  template <typename T>
  bool operator()(const T* speed_bias, T* r) const {
    for (int i = 0; i < 3; ++i) r[i] = T(weight) * speed_bias[kSbBiasAcc + i];
    return true;
  }
};

Pose ToPose(const Eigen::Isometry3d& T) {
  Pose x;
  PoseToParameters(T, x.data());
  return x;
}

struct Blocks {
  std::vector<Pose> poses;
  std::vector<SpeedBias> speed_biases;
  Pose extrinsic{};
  std::array<double, 2> tilt{0.0, 0.0};
};

/// Every pose's IMU state from the alignment's world and biases: attitude and position through
/// the guessed extrinsic, velocity from central differences.
Blocks InitialBlocks(const DynamicInitResult& init,
                     std::span<const StampedLidarPose> poses,
                     const Eigen::Isometry3d& T_imu_lidar) {
  Blocks b;
  std::vector<Eigen::Isometry3d> T_world_imu;
  for (const StampedLidarPose& p : poses) {
    T_world_imu.push_back(init.T_world_w0 * p.T_w0_lidar * T_imu_lidar.inverse());
  }
  const size_t n = poses.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t a = k == 0 ? 0 : k - 1, c = k + 1 < n ? k + 1 : n - 1;
    const double dt_s = 1e-9 * static_cast<double>(poses[c].t_ns - poses[a].t_ns);
    b.poses.push_back(ToPose(T_world_imu[k]));
    SpeedBias sb{};
    Eigen::Map<Eigen::Vector3d>{&sb[kSbVel]} =
        (T_world_imu[c].translation() - T_world_imu[a].translation()) / dt_s;
    Eigen::Map<Eigen::Vector3d>{&sb[kSbBiasAcc]} = init.bias_acc;
    Eigen::Map<Eigen::Vector3d>{&sb[kSbBiasGyro]} = init.bias_gyro;
    b.speed_biases.push_back(sb);
  }
  b.extrinsic = ToPose(T_imu_lidar);
  return b;
}

/// U with Uᵀ U = C⁻¹ for one LiDAR pose: C = σ_point² H⁻¹ + diag(floor²) from the
/// registration's Hessian H (a direction its scan hardly constrains, such as along a corridor,
/// gets the weight it earned), or diag(position_sigma_m², rotation_sigma_rad²) without one.
Eigen::Matrix<double, 6, 6> PoseSqrtInformation(const Eigen::Matrix<double, 6, 6>& hessian,
                                                const ExtrinsicCalibratorOptions& o) {
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  Vector6d floor_variance;
  Matrix6d covariance;
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(hessian);
  const double lambda_max = eig.eigenvalues().maxCoeff();
  if (o.hessian_point_sigma_m > 0.0 && eig.info() == Eigen::Success && lambda_max > 0.0 &&
      std::isfinite(lambda_max)) {
    const Vector6d lambda = eig.eigenvalues().cwiseMax(1e-9 * lambda_max);
    covariance =
        eig.eigenvectors() *
        (o.hessian_point_sigma_m * o.hessian_point_sigma_m * lambda.cwiseInverse()).asDiagonal() *
        eig.eigenvectors().transpose();
    floor_variance << Eigen::Vector3d::Constant(o.hessian_floor_position_m *
                                                o.hessian_floor_position_m),
        Eigen::Vector3d::Constant(o.hessian_floor_rotation_rad * o.hessian_floor_rotation_rad);
  } else {
    covariance.setZero();
    floor_variance << Eigen::Vector3d::Constant(o.position_sigma_m * o.position_sigma_m),
        Eigen::Vector3d::Constant(o.rotation_sigma_rad * o.rotation_sigma_rad);
  }
  covariance.diagonal() += floor_variance;
  return Eigen::LLT<Matrix6d>(covariance.inverse()).matrixU();
}

class Calibration {
 public:
  Calibration(const EstimatorConfig& config,
              std::span<const StampedLidarPose> poses,
              std::span<const ImuSample> imu,
              const Eigen::Isometry3d& guess,
              const Eigen::Isometry3d& T_world_w0,
              const ExtrinsicCalibratorOptions& options)
      : config_(config),
        poses_(poses),
        imu_(imu),
        guess_(guess),
        T_world_w0_(T_world_w0),
        options_(options) {
    for (const StampedLidarPose& p : poses_) {
      nominal_sqrt_information_.push_back(PoseSqrtInformation(p.hessian, options_));
    }
  }

  /// Builds and solves the problem at the blocks' biases, and with `covariance` computes the
  /// extrinsic's covariance at the solution; false when an IMU interval fails.
  bool Solve(Blocks* b, bool covariance, ceres::Solver::Summary* summary) {
    ceres::Problem problem(ProblemOptions());
    if (!Build(b, robust_, &problem)) return false;
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    so.max_num_iterations = options_.max_iterations;
    so.num_threads = 1;
    ceres::Solve(so, &problem, summary);
    if (covariance && summary->IsSolutionUsable()) {
      // The Gaussian covariance at the robust solution: the Cauchy loss's down-weighting of
      // typical residuals would inflate it (and hide directions the motion determined).
      ceres::Problem gaussian(ProblemOptions());
      covariance_ok_ = Build(b, /*robust=*/false, &gaussian) && ExtrinsicCovariance(b, &gaussian);
    }
    return summary->IsSolutionUsable();
  }

  const Eigen::Matrix<double, 6, 6>& covariance() const { return covariance_; }
  bool covariance_ok() const { return covariance_ok_; }

  /// From the LiDAR pose residuals at `b`: the factor s on every pose's σ that makes their
  /// median whitened squared norm that of χ²(6) (a robust variance-component estimate; the
  /// Hessian's σ_point is only a nominal figure), and the Cauchy loss from then on.
  void RescalePoseNoise(const Blocks& b) {
    std::vector<double> squared_norms;
    for (const Eigen::Matrix<double, 6, 1>& r : WhitenedPoseResiduals(b)) {
      squared_norms.push_back(r.squaredNorm());
    }
    if (squared_norms.empty()) return;
    auto mid = squared_norms.begin() + static_cast<std::ptrdiff_t>(squared_norms.size() / 2);
    std::nth_element(squared_norms.begin(), mid, squared_norms.end());
    constexpr double kChi2Dof6Median = 5.348;
    const double scale = pose_sigma_scale_ * std::sqrt(*mid / kChi2Dof6Median);
    if (std::isfinite(scale) && scale > 0.0) pose_sigma_scale_ = scale;
    robust_ = true;
  }
  double pose_sigma_scale() const { return pose_sigma_scale_; }

  /// The integrated autocorrelation time of the whitened pose residuals at `b`, in poses (the
  /// largest over their six components, each summed over lags while positive, up to
  /// `max_lag`): odometry errors persist over several sweeps, so the poses carry about 1/τ of
  /// the information the independent-noise covariance assumes.
  double ResidualCorrelationTime(const Blocks& b, size_t max_lag) const {
    const std::vector<Eigen::Matrix<double, 6, 1>> r = WhitenedPoseResiduals(b);
    double tau = 1.0;
    for (int c = 0; c < 6; ++c) {
      double r0 = 0.0;
      for (const auto& x : r) r0 += x(c) * x(c);
      if (!(r0 > 0.0)) continue;
      double tau_c = 1.0;
      for (size_t lag = 1; lag <= max_lag && lag < r.size(); ++lag) {
        double rl = 0.0;
        for (size_t k = 0; k + lag < r.size(); ++k) rl += r[k](c) * r[k + lag](c);
        if (rl <= 0.0) break;
        tau_c += 2.0 * rl / r0;
      }
      tau = std::max(tau, tau_c);
    }
    return tau;
  }

 private:
  static ceres::Problem::Options ProblemOptions() {
    ceres::Problem::Options po;
    po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return po;
  }

  bool Build(Blocks* b, bool robust, ceres::Problem* problem) {
    if (!AddImuFactors(b, problem)) return false;
    AddLidarPoses(b, robust, problem);
    AddPriors(b, problem);
    return true;
  }

  bool AddImuFactors(Blocks* b, ceres::Problem* problem) {
    for (size_t k = 0; k + 1 < poses_.size(); ++k) {
      const SpeedBias& sb = b->speed_biases[k];
      Preintegrator pre(config_.imu_noise, Eigen::Map<const Eigen::Vector3d>(&sb[kSbBiasGyro]),
                        Eigen::Map<const Eigen::Vector3d>(&sb[kSbBiasAcc]));
      if (pre.Integrate(imu_, poses_[k].t_ns, poses_[k + 1].t_ns) != PreintegrationStatus::kOk) {
        return false;
      }
      std::unique_ptr<ImuFactor> f =
          ImuFactor::Create(pre.result(), config_.imu_noise, config_.gravity_mps2);
      if (f == nullptr) return false;
      problem->AddResidualBlock(f.release(), nullptr, b->poses[k].data(), b->speed_biases[k].data(),
                                b->poses[k + 1].data(), b->speed_biases[k + 1].data());
    }
    for (Pose& p : b->poses) problem->SetManifold(p.data(), &manifold_);
    return true;
  }

  LidarPoseResidual PoseResidual(size_t k) const {
    const Eigen::Isometry3d T = T_world_w0_ * poses_[k].T_w0_lidar;
    return {Eigen::Quaterniond(T.linear()), T.translation(),
            nominal_sqrt_information_[k] / pose_sigma_scale_};
  }

  /// Every LiDAR pose residual at `b`, whitened as in the problem.
  std::vector<Eigen::Matrix<double, 6, 1>> WhitenedPoseResiduals(const Blocks& b) const {
    std::vector<Eigen::Matrix<double, 6, 1>> r(poses_.size());
    for (size_t k = 0; k < poses_.size(); ++k) {
      PoseResidual(k)(b.poses[k].data(), b.extrinsic.data(), b.tilt.data(), r[k].data());
    }
    return r;
  }

  void AddLidarPoses(Blocks* b, bool robust, ceres::Problem* problem) {
    for (size_t k = 0; k < poses_.size(); ++k) {
      auto* cost = new ceres::AutoDiffCostFunction<LidarPoseResidual, 6, kPoseSize, kPoseSize, 2>(
          new LidarPoseResidual(PoseResidual(k)));
      ceres::LossFunction* loss =
          robust ? new ceres::CauchyLoss(options_.pose_cauchy_scale) : nullptr;
      problem->AddResidualBlock(cost, loss, b->poses[k].data(), b->extrinsic.data(),
                                b->tilt.data());
    }
    problem->SetManifold(b->extrinsic.data(), &manifold_);
  }

  void AddPriors(Blocks* b, ceres::Problem* problem) {
    auto* extrinsic =
        new ceres::AutoDiffCostFunction<PosePriorResidual, 6, kPoseSize>(new PosePriorResidual{
            Eigen::Quaterniond(guess_.linear()), guess_.translation(),
            1.0 / options_.extrinsic_prior_sigma_m, 1.0 / options_.extrinsic_prior_sigma_rad});
    problem->AddResidualBlock(extrinsic, nullptr, b->extrinsic.data());
    auto* acc = new ceres::AutoDiffCostFunction<AccBiasPriorResidual, 3, kSpeedBiasSize>(
        new AccBiasPriorResidual{1.0 / options_.acc_bias_prior_sigma_mps2});
    problem->AddResidualBlock(acc, nullptr, b->speed_biases.front().data());
  }

  bool ExtrinsicCovariance(Blocks* b, ceres::Problem* problem) {
    ceres::Covariance::Options co;
    co.num_threads = 1;
    ceres::Covariance covariance(co);
    const std::vector<std::pair<const double*, const double*>> pairs = {
        {b->extrinsic.data(), b->extrinsic.data()}};
    if (!covariance.Compute(pairs, problem)) return false;
    return covariance.GetCovarianceMatrixInTangentSpace({b->extrinsic.data()}, covariance_.data());
  }

  const EstimatorConfig& config_;
  std::span<const StampedLidarPose> poses_;
  std::span<const ImuSample> imu_;
  Eigen::Isometry3d guess_;
  Eigen::Isometry3d T_world_w0_;
  const ExtrinsicCalibratorOptions& options_;
  PoseManifold manifold_;
  /// Per pose, PoseSqrtInformation before the rescaling by pose_sigma_scale_.
  std::vector<Eigen::Matrix<double, 6, 6>> nominal_sqrt_information_;
  Eigen::Matrix<double, 6, 6> covariance_ = Eigen::Matrix<double, 6, 6>::Zero();
  double pose_sigma_scale_ = 1.0;
  bool covariance_ok_ = false;
  bool robust_ = false;
};

/// RMS of the LiDAR pose residuals (unwhitened) at the solution.
void PoseResiduals(const Blocks& b,
                   std::span<const StampedLidarPose> poses,
                   const Eigen::Isometry3d& T_world_w0,
                   ExtrinsicCalibration* out) {
  const Eigen::Isometry3d T_il = PoseFromParameters(b.extrinsic.data());
  // The tilt block is the same Exp([a, b, 0]) as the window's map tilt (LidarPoseResidual).
  const Eigen::Isometry3d tilt(GravityTiltRotation(b.tilt.data()));
  double sp = 0.0, sr = 0.0;
  for (size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Isometry3d meas = tilt * T_world_w0 * poses[k].T_w0_lidar;
    const Eigen::Isometry3d est = PoseFromParameters(b.poses[k].data()) * T_il;
    sp += (est.translation() - meas.translation()).squaredNorm();
    const double a = Eigen::AngleAxisd(est.linear().transpose() * meas.linear()).angle();
    sr += a * a;
  }
  const double n = static_cast<double>(poses.size());
  out->position_rms_m = std::sqrt(sp / n);
  out->rotation_rms_rad = std::sqrt(sr / n);
}

/// The estimate's change from the guess kept only along the covariance's eigen-directions with
/// σ ≤ max_sigma_m (an unobserved direction wanders within its prior otherwise).
Eigen::Vector3d DeterminedTranslation(const Eigen::Vector3d& guess,
                                      const Eigen::Vector3d& estimate,
                                      const Eigen::Matrix3d& covariance,
                                      double max_sigma_m,
                                      int* kept) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(covariance);
  Eigen::Vector3d change = Eigen::Vector3d::Zero();
  *kept = 0;
  for (int i = 0; i < 3; ++i) {
    if (!(eig.eigenvalues()(i) <= max_sigma_m * max_sigma_m)) continue;
    const Eigen::Vector3d u = eig.eigenvectors().col(i);
    change += u * u.dot(estimate - guess);
    ++*kept;
  }
  return guess + change;
}

}  // namespace

ExtrinsicCalibration CalibrateExtrinsic(const EstimatorConfig& config,
                                        std::span<const StampedLidarPose> poses,
                                        std::span<const ImuSample> imu,
                                        const Eigen::Isometry3d& T_imu_lidar_guess,
                                        const ExtrinsicCalibratorOptions& options) {
  ExtrinsicCalibration out;
  out.T_imu_lidar = T_imu_lidar_guess;
  if (poses.size() < 2 || poses.size() < static_cast<size_t>(options.alignment.min_frames)) {
    out.message = "too few poses";
    return out;
  }
  // Gravity and biases from the first stretch (the alignment's linear solve is dense in the
  // poses). A wrong extrinsic shows there as inconsistency: its result still starts the solve.
  const size_t n_align = std::min<size_t>(poses.size(), kAlignmentPoses);
  const DynamicInitResult init = DynamicInitializer(config, options.alignment)
                                     .Solve(poses.first(n_align), imu, T_imu_lidar_guess);
  if (init.states.size() != n_align) {
    out.message =
        std::string("alignment failed: ") + std::string(DynamicInitStatusReason(init.status));
    return out;
  }
  Blocks blocks = InitialBlocks(init, poses, T_imu_lidar_guess);
  Calibration calibration(config, poses, imu, T_imu_lidar_guess, init.T_world_w0, options);
  for (int round = 0; round < 2; ++round) {  // the second at the first one's biases
    ceres::Solver::Summary summary;
    if (!calibration.Solve(&blocks, /*covariance=*/round == 1, &summary)) {
      out.message = "solve failed: " + summary.message;
      return out;
    }
    out.iterations += static_cast<int>(summary.iterations.size());
    if (round == 0) calibration.RescalePoseNoise(blocks);
  }
  if (!calibration.covariance_ok()) {
    out.message = "the extrinsic's covariance is rank deficient";
    return out;
  }
  out.pose_sigma_scale = calibration.pose_sigma_scale();
  out.correlation_poses = calibration.ResidualCorrelationTime(blocks, kMaxCorrelationLag);
  out.covariance = calibration.covariance() * out.correlation_poses;
  PoseResiduals(blocks, poses, init.T_world_w0, &out);
  // What the motion determines is judged on the independent-noise covariance (the gates'
  // figures were set on it); the correlation only scales the accuracy reported.
  const Eigen::Matrix<double, 6, 6>& determined = calibration.covariance();
  // Rotation about one axis only (a planar drive without turns) leaves the extrinsic's rotation
  // about the other two to the prior: refuse rather than report the wander (measured on the
  // straight `short` drive: 15° off with σ 4.9°).
  const double sigma_rotation_rad = std::sqrt(determined.diagonal().tail<3>().maxCoeff());
  if (sigma_rotation_rad > options.max_rotation_sigma_rad) {
    out.message = "the motion does not determine the rotation (σ " +
                  std::to_string(sigma_rotation_rad * 180.0 / 3.14159265358979323846) +
                  "°): it needs turns";
    return out;
  }
  out.ok = true;
  out.T_imu_lidar = PoseFromParameters(blocks.extrinsic.data());
  out.T_imu_lidar.translation() =
      DeterminedTranslation(T_imu_lidar_guess.translation(), out.T_imu_lidar.translation(),
                            determined.topLeftCorner<3, 3>(), options.max_translation_sigma_m,
                            &out.translation_directions);
  const SpeedBias& last = blocks.speed_biases.back();
  out.bias_acc = Eigen::Map<const Eigen::Vector3d>(&last[kSbBiasAcc]);
  out.bias_gyro = Eigen::Map<const Eigen::Vector3d>(&last[kSbBiasGyro]);
  return out;
}

}  // namespace swlio::estimator

#include "swlio/estimator/init/dynamic_initializer.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/estimator/imu/preintegration.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using MatX = Eigen::MatrixXd;
using VecX = Eigen::VectorXd;

/// Floors of the IMU rows' standard deviations: the pre-integrated covariance alone (white
/// noise) ignores the bias walk and the discretization; 0.1 mm and 0.1 mm/s per interval.
constexpr double kImuPositionFloorM = 1e-4;
constexpr double kImuVelocityFloorMps = 1e-4;

/// IMU pose in w0 at a LiDAR pose time.
struct Frame {
  int64_t t_ns = 0;
  Mat3 R = Mat3::Identity();  ///< R_w0_imu
  Vec3 p = Vec3::Zero();      ///< p_w0_imu
};

std::vector<Frame> ImuFrames(std::span<const StampedLidarPose> poses,
                             const Eigen::Isometry3d& T_imu_lidar) {
  const Eigen::Isometry3d T_lidar_imu = T_imu_lidar.inverse();
  std::vector<Frame> frames;
  frames.reserve(poses.size());
  for (const StampedLidarPose& pose : poses) {
    const Eigen::Isometry3d T_w0_imu = pose.T_w0_lidar * T_lidar_imu;
    frames.push_back({pose.t_ns, T_w0_imu.linear(), T_w0_imu.translation()});
  }
  return frames;
}

bool ValidPoses(std::span<const StampedLidarPose> poses) {
  for (size_t k = 0; k < poses.size(); ++k) {
    if (!poses[k].T_w0_lidar.matrix().allFinite()) return false;
    if (k > 0 && poses[k].t_ns <= poses[k - 1].t_ns) return false;
  }
  return true;
}

/// Largest standard deviation of a covariance block.
double MaxStd(const MatX& P) {
  const Eigen::SelfAdjointEigenSolver<MatX> eig(P, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
}

/// Pre-integrates every interval at zero biases; false when the samples do not cover them.
bool IntegrateIntervals(const std::vector<Frame>& frames,
                        std::span<const ImuSample> imu,
                        const ImuNoiseConfig& noise,
                        std::vector<Preintegrator>& pims) {
  for (size_t i = 0; i + 1 < frames.size(); ++i) {
    Preintegrator p(noise, Vec3::Zero(), Vec3::Zero());
    if (p.Integrate(imu, frames[i].t_ns, frames[i + 1].t_ns) != PreintegrationStatus::kOk) {
      return false;
    }
    pims.push_back(std::move(p));
  }
  return true;
}

// ---- Step (1): gyro bias ------------------------------------------------------------------

struct GyroSystem {
  Mat6 H = Mat6::Zero();  ///< whitened normal matrix of [θ; δb_g]
  Vec6 rhs = Vec6::Zero();
  std::vector<Eigen::Matrix<double, 3, 6>> A;  ///< rows of frames 1..N (unwhitened)
  std::vector<Vec3> y;
};

/// y_k = Log(ΔR_0kᵀ R_0ᵀ R_k) ≈ ΔR_0kᵀ θ + J_0k δb_g, plus the prior row θ ≈ 0.
GyroSystem BuildGyroSystem(const std::vector<Frame>& frames,
                           const std::vector<Preintegrator>& pims,
                           double sigma_rad) {
  GyroSystem s;
  const double w2 = 1.0 / (sigma_rad * sigma_rad);
  s.H.topLeftCorner<3, 3>() = w2 * Mat3::Identity();
  Mat3 dR = Mat3::Identity();
  Mat3 J = Mat3::Zero();
  for (size_t k = 1; k < frames.size(); ++k) {
    const PreintegratedImu& pim = pims[k - 1].result();
    J = pim.delta_R.transpose() * J + pim.J_R_bg();
    dR = dR * pim.delta_R;
    Eigen::Matrix<double, 3, 6> A;
    A << dR.transpose(), J;
    const Vec3 y = lie::Log(dR.transpose() * frames[0].R.transpose() * frames[k].R);
    s.H += w2 * A.transpose() * A;
    s.rhs += w2 * A.transpose() * y;
    s.A.push_back(A);
    s.y.push_back(y);
  }
  return s;
}

struct GyroFit {
  Vec3 bias = Vec3::Zero();
  Vec3 std = Vec3::Zero();
  double rms_rad = 0.0;
};

GyroFit FitGyroBias(const std::vector<Frame>& frames,
                    std::vector<Preintegrator>& pims,
                    const DynamicInitializer::Options& options) {
  GyroFit fit;
  for (int it = 0; it < options.gyro_iterations; ++it) {
    const GyroSystem s = BuildGyroSystem(frames, pims, options.rotation_sigma_rad);
    fit.bias += s.H.ldlt().solve(s.rhs).tail<3>();
    for (Preintegrator& p : pims) p.Reintegrate(fit.bias, Vec3::Zero());
  }
  const GyroSystem s = BuildGyroSystem(frames, pims, options.rotation_sigma_rad);
  const Vec6 x = s.H.ldlt().solve(s.rhs);
  double sum2 = 0.0;
  for (size_t k = 0; k < s.y.size(); ++k) sum2 += (s.y[k] - s.A[k] * x).squaredNorm();
  fit.rms_rad = std::sqrt(sum2 / static_cast<double>(3 * s.y.size()));
  fit.std = s.H.inverse().bottomRightCorner<3, 3>().diagonal().cwiseSqrt();
  return fit;
}

// ---- Steps (2) and (3): velocities, gravity, accelerometer bias ----------------------------

/// Gravity model of one solve: free 3-vector (2), or G·(ĝ + B δ) with b_a (3).
struct GravityModel {
  bool refine = false;
  double G = 0.0;
  Vec3 g_hat = Vec3::Zero();
  Eigen::Matrix<double, 3, 2> B = Eigen::Matrix<double, 3, 2>::Zero();
};

GravityModel RefineModel(const Vec3& g_dir, double G) {
  GravityModel m;
  m.refine = true;
  m.G = G;
  m.g_hat = g_dir.normalized();
  const Vec3 b1 = m.g_hat.unitOrthogonal();
  m.B << b1, m.g_hat.cross(b1);
  return m;
}

/// Unknown layout: p_0..p_N, v_0..v_N, gravity (3 free / 2 tangent), b_a (refine only).
struct Layout {
  int n = 0;  ///< frames
  int v0 = 0, g = 0, ba = 0, size = 0;
  Layout(int frames, bool refine)
      : n(frames),
        v0(3 * frames),
        g(6 * frames),
        ba(g + (refine ? 2 : 3)),
        size(ba + (refine ? 3 : 0)) {}
  int P(size_t k) const { return 3 * static_cast<int>(k); }
  int V(size_t k) const { return v0 + 3 * static_cast<int>(k); }
};

/// Whitened linear system A x = b.
struct AlignSystem {
  MatX A;
  VecX b;
  int lidar_rows = 0;  ///< the first rows: LiDAR positions
};

/// Rows of interval i → i+1 (see the header, step 2), whitened.
void AddImuRows(const Frame& fi,
                const PreintegratedImu& pim,
                const Layout& L,
                size_t i,
                const GravityModel& m,
                double sigma_rot,
                AlignSystem& s,
                int row) {
  const double dt = pim.dt_s;
  const Mat3 I = Mat3::Identity();
  const double sp = std::sqrt(pim.covariance.block<3, 3>(kRowP, kRowP).trace() / 3.0 +
                              std::pow(sigma_rot * pim.delta_p.norm(), 2) +
                              kImuPositionFloorM * kImuPositionFloorM);
  const double sv = std::sqrt(pim.covariance.block<3, 3>(kRowV, kRowV).trace() / 3.0 +
                              std::pow(sigma_rot * pim.delta_v.norm(), 2) +
                              kImuVelocityFloorMps * kImuVelocityFloorMps);
  auto A = [&](int r, int c) { return s.A.block<3, 3>(row + r, c); };
  A(0, L.P(i + 1)) = I / sp;
  A(0, L.P(i)) = -I / sp;
  A(0, L.V(i)) = -dt * I / sp;
  A(3, L.V(i + 1)) = I / sv;
  A(3, L.V(i)) = -I / sv;
  Vec3 bp = fi.R * pim.delta_p;
  Vec3 bv = fi.R * pim.delta_v;
  if (m.refine) {
    s.A.block<3, 2>(row, L.g) = -0.5 * dt * dt * m.G * m.B / sp;
    s.A.block<3, 2>(row + 3, L.g) = -dt * m.G * m.B / sv;
    A(0, L.ba) = -fi.R * pim.J_p_ba() / sp;
    A(3, L.ba) = -fi.R * pim.J_v_ba() / sv;
    bp += 0.5 * dt * dt * m.G * m.g_hat;
    bv += dt * m.G * m.g_hat;
  } else {
    A(0, L.g) = -0.5 * dt * dt * I / sp;
    A(3, L.g) = -dt * I / sv;
  }
  s.b.segment<3>(row) = bp / sp;
  s.b.segment<3>(row + 3) = bv / sv;
}

AlignSystem BuildAlignSystem(const std::vector<Frame>& frames,
                             const std::vector<Preintegrator>& pims,
                             const GravityModel& m,
                             const Layout& L,
                             double sigma_pos,
                             const DynamicInitializer::Options& o) {
  const int n = L.n;
  AlignSystem s;
  s.lidar_rows = 3 * n;
  const int rows = 3 * n + 6 * (n - 1) + (m.refine ? 3 : 0);
  s.A = MatX::Zero(rows, L.size);
  s.b = VecX::Zero(rows);
  for (size_t k = 0; k < frames.size(); ++k) {
    s.A.block<3, 3>(L.P(k), L.P(k)) = Mat3::Identity() / sigma_pos;
    s.b.segment<3>(L.P(k)) = frames[k].p / sigma_pos;
  }
  for (size_t i = 0; i + 1 < frames.size(); ++i) {
    AddImuRows(frames[i], pims[i].result(), L, i, m, o.rotation_sigma_rad, s,
               3 * n + 6 * static_cast<int>(i));
  }
  if (m.refine) {
    s.A.block<3, 3>(rows - 3, L.ba) = Mat3::Identity() / o.acc_bias_prior_sigma_mps2;
  }
  return s;
}

struct AlignFit {
  VecX x;
  MatX P;  ///< covariance H⁻¹
  Vec3 gravity = Vec3::Zero();
  double normalized_cost = 0.0;
  double position_rms_m = 0.0;
  double condition_number = 0.0;
};

AlignFit SolveAlign(const AlignSystem& s, double sigma_pos) {
  AlignFit f;
  const MatX H = s.A.transpose() * s.A;
  const Eigen::LDLT<MatX> ldlt(H);
  f.x = ldlt.solve(s.A.transpose() * s.b);
  f.P = ldlt.solve(MatX::Identity(H.rows(), H.cols()));
  const VecX r = s.A * f.x - s.b;
  const auto dof = static_cast<double>(std::max<Eigen::Index>(r.size() - f.x.size(), 1));
  f.normalized_cost = r.squaredNorm() / dof;
  f.position_rms_m = sigma_pos * std::sqrt(r.head(s.lidar_rows).squaredNorm() / s.lidar_rows);
  const VecX d = H.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::SelfAdjointEigenSolver<MatX> eig(d.asDiagonal() * H * d.asDiagonal(),
                                                Eigen::EigenvaluesOnly);
  f.condition_number =
      eig.eigenvalues().maxCoeff() / std::max(eig.eigenvalues().minCoeff(), 1e-300);
  return f;
}

// ---- Step (4): gravity-aligned world -------------------------------------------------------

Eigen::Isometry3d WorldFromW0(const Vec3& gravity_w0, const Frame& first) {
  const Mat3 R_align =
      Eigen::Quaterniond::FromTwoVectors(-gravity_w0, Vec3::UnitZ()).toRotationMatrix();
  const double yaw = lie::RpyFromRotation(R_align * first.R).z();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(-yaw, Vec3::UnitZ()).toRotationMatrix() * R_align;
  T.translation() = -(T.linear() * first.p);
  return T;
}

/// Steps (2) and (3); fills the gravity, b_a and the solve's quality figures of `res`.
void Align(const std::vector<Frame>& frames,
           const std::vector<Preintegrator>& pims,
           double G,
           double sigma_pos,
           const DynamicInitializer::Options& o,
           DynamicInitResult& res) {
  const int n = static_cast<int>(frames.size());
  const Layout free_layout(n, false);
  const AlignFit free = SolveAlign(
      BuildAlignSystem(frames, pims, GravityModel{}, free_layout, sigma_pos, o), sigma_pos);
  const Vec3 g_free = free.x.segment<3>(free_layout.g);
  res.gravity_norm_free_mps2 = g_free.norm();
  if (!g_free.allFinite() || g_free.norm() < 0.1 * G) return;
  const Vec3 u = g_free.normalized();
  res.gravity_norm_free_std_mps2 =
      std::sqrt(u.dot(free.P.block<3, 3>(free_layout.g, free_layout.g) * u));

  const Layout L(n, true);
  GravityModel m = RefineModel(g_free, G);
  AlignFit fit;
  for (int it = 0; it < std::max(o.gravity_iterations, 1); ++it) {
    fit = SolveAlign(BuildAlignSystem(frames, pims, m, L, sigma_pos, o), sigma_pos);
    m = RefineModel(m.g_hat + m.B * fit.x.segment<2>(L.g), G);
  }
  res.gravity_w0 = G * m.g_hat;
  res.bias_acc = fit.x.segment<3>(L.ba);
  const MatX P_ba = fit.P.block(L.ba, L.ba, 3, 3);
  res.bias_acc_std = P_ba.diagonal().cwiseSqrt();
  res.acc_bias_observable = MaxStd(P_ba) <= o.max_acc_bias_std_mps2;
  res.gravity_tilt_std_rad = MaxStd(fit.P.block(L.g, L.g, 2, 2));
  res.velocity_std_mps = MaxStd(fit.P.block(L.V(frames.size() - 1), L.V(frames.size() - 1), 3, 3));
  res.position_rms_m = fit.position_rms_m;
  res.normalized_cost = fit.normalized_cost;
  res.condition_number = fit.condition_number;
  for (size_t k = 0; k < frames.size(); ++k) {
    State s;
    s.t_ns = frames[k].t_ns;
    s.T_world_imu.linear() = frames[k].R;
    s.T_world_imu.translation() = frames[k].p;
    s.vel_world = fit.x.segment<3>(L.V(k));
    res.states.push_back(s);  // still in w0: moved into the world by the caller
  }
}

/// Normalized residuals first (valid however weak the constraints), then the constraint
/// strength, then the plausibility of |g| and b_g (judged with their own uncertainty).
DynamicInitStatus Classify(const DynamicInitResult& r,
                           double G,
                           const DynamicInitializer::Options& o) {
  using enum DynamicInitStatus;
  if (r.states.empty() || r.rotation_rms_rad > o.max_normalized_rms * o.rotation_sigma_rad ||
      r.normalized_cost > o.max_normalized_rms * o.max_normalized_rms) {
    return kInconsistent;
  }
  if (r.gravity_tilt_std_rad > o.max_gravity_tilt_std_rad ||
      r.velocity_std_mps > o.max_velocity_std_mps) {
    return kPoorlyConstrained;
  }
  const double g_error = std::abs(r.gravity_norm_free_mps2 - G);
  if (g_error > o.max_gravity_norm_error_mps2 + 3.0 * r.gravity_norm_free_std_mps2 ||
      r.bias_gyro.norm() > o.max_gyro_bias_radps + 3.0 * r.bias_gyro_std.norm()) {
    return kInconsistent;
  }
  if (o.require_acc_bias && !r.acc_bias_observable) return kPoorlyConstrained;
  return kOk;
}

}  // namespace

std::string_view DynamicInitStatusReason(DynamicInitStatus status) {
  switch (status) {
    case DynamicInitStatus::kOk:
      return "initialized";
    case DynamicInitStatus::kTooFewFrames:
      return "too few LiDAR poses";
    case DynamicInitStatus::kBadInput:
      return "pose times not increasing or non-finite poses";
    case DynamicInitStatus::kImuNotCovered:
      return "IMU samples do not cover the poses";
    case DynamicInitStatus::kInconsistent:
      return "LiDAR poses and IMU disagree (extrinsic, time offset or odometry)";
    case DynamicInitStatus::kPoorlyConstrained:
      return "motion or pose quality too weak for the required accuracy";
  }
  return "unknown";
}

DynamicInitializer::DynamicInitializer(const EstimatorConfig& config)
    : DynamicInitializer(config, Options{}) {}

DynamicInitializer::DynamicInitializer(const EstimatorConfig& config, const Options& options)
    : gravity_mps2_(config.gravity_mps2), noise_(config.imu_noise), options_(options) {}

DynamicInitResult DynamicInitializer::Solve(std::span<const StampedLidarPose> poses,
                                            std::span<const ImuSample> imu,
                                            const Eigen::Isometry3d& T_imu_lidar) const {
  DynamicInitResult res;
  if (poses.size() < static_cast<size_t>(std::max(options_.min_frames, 3))) return res;
  if (!ValidPoses(poses) || !T_imu_lidar.matrix().allFinite()) {
    res.status = DynamicInitStatus::kBadInput;
    return res;
  }
  const std::vector<Frame> frames = ImuFrames(poses, T_imu_lidar);
  std::vector<Preintegrator> pims;
  if (!IntegrateIntervals(frames, imu, noise_, pims)) {
    res.status = DynamicInitStatus::kImuNotCovered;
    return res;
  }
  for (const Frame& f : frames) {
    res.rotation_angle_rad =
        std::max(res.rotation_angle_rad, lie::Log(frames[0].R.transpose() * f.R).norm());
  }
  const GyroFit gyro = FitGyroBias(frames, pims, options_);
  res.bias_gyro = gyro.bias;
  res.bias_gyro_std = gyro.std;
  res.rotation_rms_rad = gyro.rms_rad;

  const double sigma_pos = std::hypot(
      options_.position_sigma_m, options_.rotation_sigma_rad * T_imu_lidar.translation().norm());
  Align(frames, pims, gravity_mps2_, sigma_pos, options_, res);
  res.status = Classify(res, gravity_mps2_, options_);
  if (res.states.empty()) return res;

  res.T_world_w0 = WorldFromW0(res.gravity_w0, frames[0]);
  const Mat3 R_world_w0 = res.T_world_w0.linear();
  for (State& s : res.states) {
    s.T_world_imu = res.T_world_w0 * s.T_world_imu;
    s.vel_world = R_world_w0 * s.vel_world;
    s.bias_gyro = res.bias_gyro;
    s.bias_acc = res.bias_acc;
  }
  return res;
}

}  // namespace swlio::estimator

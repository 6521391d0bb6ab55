#include "swlio/estimator/window/time_offset_estimator.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "swlio/core/lie.h"
#include "swlio/core/time.h"

namespace swlio::estimator {

namespace {

constexpr int64_t kMaxImuGapNs = 20'000'000;  ///< a wider gap between samples: no row
constexpr int64_t kStepDNs = 500'000;         ///< central difference in d (0.5 ms)
constexpr double kStepBiasRadps = 1e-3;       ///< central difference in b_g
constexpr int64_t kImuKeptNs = 3 * kNsPerSec;
constexpr size_t kRowsPerSolve = 300;

int64_t ToNs(double s) { return static_cast<int64_t>(std::llround(s * 1e9)); }

}  // namespace

ConfigIssues TimeOffsetConfig::Validate() const {
  ConfigIssues issues;
  CheckInRange(issues, "max_offset_s", max_offset_s, 0.0, 0.2);
  CheckInRange(issues, "initial_offset_s", initial_offset_s, -max_offset_s, max_offset_s);
  CheckInRange(issues, "span_s", span_s, 0.1, 2.0);
  CheckInRange(issues, "history_s", history_s, 1.0, 600.0);
  CheckPositive(issues, "gate_sigma_s", gate_sigma_s);
  CheckInRange(issues, "coarse_gate_sigma_s", coarse_gate_sigma_s, 0.0, 0.01);
  CheckInRange<size_t>(issues, "min_rows", min_rows, 4, 100000);
  // Above 1 ms a step could reorder the shifted samples of a 400 Hz IMU (2.5 ms apart) and
  // jump the IMU factors.
  CheckInRange(issues, "max_step_s", max_step_s, 0.0, 1e-3);
  CheckPositive(issues, "huber_rad", huber_rad);
  CheckInRange(issues, "tilt_weight", tilt_weight, 0.0, 1.0);
  CheckInRange(issues, "operating_point_tolerance_s", operating_point_tolerance_s, 1e-4, 0.05);
  CheckInRange(issues, "correlated_rows", correlated_rows, 0, 1000);
  CheckInRange(issues, "initial_sigma_s", initial_sigma_s, 0.0, 0.05);
  CheckInRange(issues, "window_prior_sigma_s", window_prior_sigma_s, 0.0, 0.05);
  return issues;
}

TimeOffsetEstimator::TimeOffsetEstimator(const TimeOffsetConfig& config)
    : config_(config),
      target_s_(config.enabled ? config.initial_offset_s : 0.0),
      offset_ns_(ToNs(target_s_)) {
  status_.enabled = config_.enabled;
  status_.offset_s = status_.estimate_s = target_s_;
  x_(0) = target_s_;
}

void TimeOffsetEstimator::AddImu(const ImuSample& sample) {
  if (!config_.enabled || !config_.estimate) return;
  if (!imu_.empty() && sample.t_ns <= imu_.back().t_ns) return;
  imu_.push_back(sample);
  while (imu_.front().t_ns < sample.t_ns - kImuKeptNs) imu_.pop_front();
  FormRows();
}

ImuSample TimeOffsetEstimator::Shifted(ImuSample sample) const {
  sample.t_ns -= offset_ns_;
  return sample;
}

double TimeOffsetEstimator::applied_sigma_s() const {
  if (!config_.enabled || !config_.estimate || config_.initial_sigma_s <= 0.0) return 0.0;
  if (status_.updates > 0) return std::hypot(gated_sigma_s_, target_s_ - status_.offset_s);
  if (status_.rows < config_.min_rows || !std::isfinite(status_.sigma_s))
    return config_.initial_sigma_s;
  return std::min(config_.initial_sigma_s,
                  std::hypot(status_.sigma_s, status_.estimate_s - status_.offset_s));
}

double TimeOffsetEstimator::followed_offset_s() const {
  return status_.updates > 0 ? target_s_ : status_.offset_s;
}

double TimeOffsetEstimator::followed_sigma_s() const {
  if (!config_.enabled || !config_.estimate || config_.initial_sigma_s <= 0.0) return 0.0;
  return status_.updates > 0 ? gated_sigma_s_ : applied_sigma_s();
}

void TimeOffsetEstimator::ForgetRows() {
  rows_.clear();
  registrations_.clear();
  status_.rows = 0;
}

std::optional<Eigen::Quaterniond> TimeOffsetEstimator::IntegrateGyro(
    const std::deque<ImuSample>& samples, int64_t a_ns, int64_t b_ns, const Eigen::Vector3d& bias) {
  if (samples.size() < 2 || a_ns >= b_ns) return std::nullopt;
  if (samples.front().t_ns > a_ns || samples.back().t_ns < b_ns) return std::nullopt;
  // The last sample at or before a.
  auto it = std::upper_bound(samples.begin(), samples.end(), a_ns,
                             [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  size_t i = static_cast<size_t>(std::distance(samples.begin(), it)) - 1;
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (; i + 1 < samples.size() && samples[i].t_ns < b_ns; ++i) {
    const ImuSample& s0 = samples[i];
    const ImuSample& s1 = samples[i + 1];
    if (s1.t_ns - s0.t_ns > kMaxImuGapNs) return std::nullopt;
    const int64_t lo = std::max(a_ns, s0.t_ns);
    const int64_t hi = std::min(b_ns, s1.t_ns);
    if (hi <= lo) continue;
    const Eigen::Vector3d w = s1.gyro_radps - bias;  // s1's interval holds [lo, hi]
    q = q * lie::QuatExp(w * static_cast<double>(hi - lo) * 1e-9);
  }
  return q.normalized();
}

std::optional<TimeOffsetEstimator::Row> TimeOffsetEstimator::MakeRow(const Registration& a,
                                                                     const Registration& b) const {
  Row row;
  row.t_ns = b.t_ns;
  row.applied_ns = (a.applied_ns + b.applied_ns) / 2;
  row.x_lin << target_s_, x_.tail<3>();
  const Eigen::Quaterniond dq_lidar = a.q_world_imu.conjugate() * b.q_world_imu;
  const int64_t d_ns = ToNs(target_s_);
  auto residual = [&](int64_t dd_ns,
                      const Eigen::Vector3d& bias) -> std::optional<Eigen::Vector3d> {
    const auto dq_gyro = IntegrateGyro(imu_, a.t_ns + d_ns + dd_ns, b.t_ns + d_ns + dd_ns, bias);
    if (!dq_gyro) return std::nullopt;
    return lie::QuatLog(dq_lidar.conjugate() * *dq_gyro);
  };
  const Eigen::Vector3d b0 = x_.tail<3>();
  const auto r0 = residual(0, b0);
  const auto r_plus = residual(kStepDNs, b0);
  const auto r_minus = residual(-kStepDNs, b0);
  if (!r0 || !r_plus || !r_minus) return std::nullopt;
  row.r = *r0;
  row.J.col(0) = (*r_plus - *r_minus) / (2e-9 * static_cast<double>(kStepDNs));
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d db = Eigen::Vector3d::Unit(k) * kStepBiasRadps;
    const auto rb_plus = residual(0, b0 + db);
    const auto rb_minus = residual(0, b0 - db);
    if (!rb_plus || !rb_minus) return std::nullopt;
    row.J.col(k + 1) = (*rb_plus - *rb_minus) / (2.0 * kStepBiasRadps);
  }
  return row;
}

void TimeOffsetEstimator::AddRegistration(int64_t t_ns, const Eigen::Quaterniond& q_world_imu) {
  if (!config_.enabled || !config_.estimate) return;
  if (!registrations_.empty() && t_ns <= registrations_.back().t_ns) return;
  registrations_.push_back({t_ns, offset_ns_, q_world_imu.normalized()});
  pending_end_ = true;
  FormRows();
  Step();
}

void TimeOffsetEstimator::FormRows() {
  if (!pending_end_ || registrations_.size() < 2 || imu_.empty()) return;
  const Registration& b = registrations_.back();
  // Wait until the samples cover the row's span at the offset it is linearized at.
  if (b.t_ns + ToNs(target_s_) + 2 * kStepDNs > imu_.back().t_ns) return;
  pending_end_ = false;
  const int64_t span_ns = ToNs(config_.span_s);
  // The start: the registration closest to span_s before b, within half a span of that.
  const Registration* a = nullptr;
  int64_t best_miss_ns = span_ns / 2;
  for (const Registration& r : registrations_) {
    const int64_t miss_ns = std::llabs(b.t_ns - r.t_ns - span_ns);
    if (r.t_ns < b.t_ns && miss_ns <= best_miss_ns) {
      a = &r;
      best_miss_ns = miss_ns;
    }
  }
  std::optional<Row> row;
  if (a != nullptr) row = MakeRow(*a, b);
  while (registrations_.front().t_ns < b.t_ns - 2 * span_ns) registrations_.pop_front();
  if (!row) return;
  rows_.push_back(*row);
  while (rows_.front().t_ns < row->t_ns - ToNs(config_.history_s)) rows_.pop_front();
  // A long history moves little with one row: solve every rows/kRowsPerSolve-th row, so a
  // sweep costs about kRowsPerSolve rows' worth however long the history.
  if (++rows_since_solve_ * kRowsPerSolve < rows_.size()) return;
  rows_since_solve_ = 0;
  Solve();
}

TimeOffsetEstimator::WeightedRow TimeOffsetEstimator::Weigh(const Row& row,
                                                            const Eigen::Vector4d& x) const {
  const Eigen::Vector3d axis_w(config_.tilt_weight, config_.tilt_weight, 1.0);
  WeightedRow out;
  out.e = axis_w.asDiagonal() * (row.r + row.J * (x - row.x_lin));
  out.J = axis_w.asDiagonal() * row.J;
  const double norm = out.e.norm();
  out.w = norm <= config_.huber_rad ? 1.0 : config_.huber_rad / norm;
  return out;
}

bool TimeOffsetEstimator::AtThisOperatingPoint(const Row& row) const {
  return std::llabs(row.applied_ns - offset_ns_) <= ToNs(config_.operating_point_tolerance_s);
}

void TimeOffsetEstimator::Solve() {
  // The rows made at the offset applied now, once they alone pass the gate, replace the
  // others; before that all rows (a start or a walk: the nearer operating points lean less).
  Fit fit = FitRows(true);
  const bool settled = fit.rows >= config_.min_rows && fit.sigma_s <= config_.gate_sigma_s;
  if (settled) {
    std::erase_if(rows_, [&](const Row& row) { return !AtThisOperatingPoint(row); });
  } else {
    fit = FitRows(false);
  }
  status_.rows = fit.rows;
  status_.residual_rms_rad = fit.rms_rad;
  status_.excitation_radps = fit.excitation_radps;
  status_.sigma_s = fit.sigma_s;
  status_.estimate_s = std::clamp(fit.x(0), -config_.max_offset_s, config_.max_offset_s);
  const double sigma_s = status_.sigma_s;
  const bool constrained =
      sigma_s <= config_.gate_sigma_s || (sigma_s <= config_.coarse_gate_sigma_s &&
                                          std::abs(status_.estimate_s - target_s_) > 3.0 * sigma_s);
  status_.gated = fit.rows >= config_.min_rows && constrained && std::isfinite(fit.x(0));
  x_.tail<3>() = fit.x.tail<3>();
  if (!status_.gated) return;
  x_(0) = target_s_ = status_.estimate_s;
  gated_sigma_s_ = sigma_s;
  ++status_.updates;
}

TimeOffsetEstimator::Fit TimeOffsetEstimator::FitRows(bool this_operating_point_only) {
  using Mat4 = Eigen::Matrix4d;
  using Vec4 = Eigen::Vector4d;
  Fit fit;
  fit.x = x_;
  fit.x(0) = target_s_;
  Vec4& x = fit.x;
  // A weak prior on b_g about its last value keeps the axes a yaw-only fit leaves open solvable.
  const Mat4 prior = Eigen::Vector4d(0.0, 1e-2, 1e-2, 1e-2).asDiagonal();
  Mat4 H;
  double weighted_sq = 0.0, excitation_sq = 0.0;
  // Gauss–Newton on rows linear in x (each about its own x_lin), reweighted twice (Huber).
  for (int iteration = 0; iteration < 3; ++iteration) {
    H = Mat4::Identity() * 1e-12 + prior;
    Vec4 g = prior * (x - x_);
    weighted_sq = excitation_sq = 0.0;
    fit.rows = 0;
    for (const Row& row : rows_) {
      if (this_operating_point_only && !AtThisOperatingPoint(row)) continue;
      const auto [e, J, w] = Weigh(row, x);
      H += w * J.transpose() * J;
      g += w * J.transpose() * e;
      weighted_sq += w * e.squaredNorm();
      excitation_sq += J.col(0).squaredNorm();
      ++fit.rows;
    }
    if (fit.rows == 0) return fit;
    x -= H.ldlt().solve(g);
  }
  const double n = static_cast<double>(fit.rows);
  const double rows_per = config_.tilt_weight > 0.0 ? 3.0 : 1.0;
  const double dof = std::max(1.0, rows_per * n - 4.0);
  fit.rms_rad = std::sqrt(weighted_sq / dof);
  fit.excitation_radps = std::sqrt(excitation_sq / n);
  const Mat4 H_inv = H.ldlt().solve(Mat4::Identity());
  // The sandwich H⁻¹ S H⁻¹ with the rows' correlation; never below the σ of independent rows
  // scaled by their RMS (with few rows the lagged sums cancel toward zero).
  const double sigma_independent_s = fit.rms_rad * std::sqrt(std::max(0.0, H_inv(0, 0)));
  const Mat4 S = CorrelatedScoreCovariance(x, this_operating_point_only);
  const double sigma_correlated_s = std::sqrt(std::max(0.0, (H_inv * S * H_inv)(0, 0)));
  fit.sigma_s = std::max(sigma_independent_s, sigma_correlated_s);
  return fit;
}

Eigen::Matrix4d TimeOffsetEstimator::CorrelatedScoreCovariance(const Eigen::Vector4d& x,
                                                               bool this_operating_point_only) {
  scores_.clear();
  for (const Row& row : rows_) {
    if (this_operating_point_only && !AtThisOperatingPoint(row)) continue;
    const auto [e, J, w] = Weigh(row, x);
    scores_.push_back(w * J.transpose() * e);
  }
  // Newey and West (Econometrica 55(3), 1987, eq. 2): the scores' covariance with their lagged
  // cross terms, Bartlett-weighted (positive semi-definite). A_k = Σ_{l=1..L} (1 − l/(L+1))
  // s_{k−l} from the running sums U = Σ s_{k−l} and V = Σ l s_{k−l}: one pass over the rows.
  const size_t lags = static_cast<size_t>(config_.correlated_rows);
  const double L1 = static_cast<double>(lags) + 1.0;
  Eigen::Matrix4d S = Eigen::Matrix4d::Zero();
  Eigen::Vector4d U = Eigen::Vector4d::Zero(), V = Eigen::Vector4d::Zero();
  for (size_t k = 0; k < scores_.size(); ++k) {
    const Eigen::Vector4d A = U - V / L1;
    const Eigen::Matrix4d cross = scores_[k] * A.transpose();
    S += scores_[k] * scores_[k].transpose() + cross + cross.transpose();
    const Eigen::Vector4d dropped = k >= lags ? scores_[k - lags] : Eigen::Vector4d::Zero();
    V += scores_[k] + U - L1 * dropped;
    U += scores_[k] - dropped;
  }
  return S;
}

void TimeOffsetEstimator::Step() {
  const int64_t step_ns = ToNs(config_.max_step_s);
  const int64_t to_ns = ToNs(target_s_);
  offset_ns_ += std::clamp(to_ns - offset_ns_, -step_ns, step_ns);
  status_.offset_s = NsToSec(offset_ns_);
}

}  // namespace swlio::estimator

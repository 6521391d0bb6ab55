#include "swlio/estimator/imu/imu_stillness.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_moments.h"

namespace swlio::estimator {
namespace {

using Vec3 = Eigen::Vector3d;

/// Hann-weighted means of acc and gyro over samples [begin, end).
void HannMeans(std::span<const ImuSample> samples, Vec3* acc, Vec3* gyro) {
  const size_t n = samples.size();
  *acc = Vec3::Zero();
  *gyro = Vec3::Zero();
  double weight_sum = 0.0;
  for (size_t k = 0; k < n; ++k) {
    // Periodic Hann over n + 1 points without the zero ends: every sample counts.
    const double x = static_cast<double>(k + 1) / static_cast<double>(n + 1);
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * x);
    *acc += w * samples[k].acc_mps2;
    *gyro += w * samples[k].gyro_radps;
    weight_sum += w;
  }
  *acc /= weight_sum;
  *gyro /= weight_sum;
}

/// Excursion (largest per-axis |u − ū|) and RMS of u(t) = ∫ (get − mean) dt about its mean.
template <typename Get>
void Excursion(
    std::span<const ImuSample> samples, const Vec3& mean, Get get, double* excursion, double* rms) {
  std::vector<Vec3> u(samples.size(), Vec3::Zero());
  for (size_t k = 1; k < samples.size(); ++k) {
    const double dt = NsToSec(samples[k].t_ns - samples[k - 1].t_ns);
    u[k] = u[k - 1] + 0.5 * dt * (get(samples[k]) + get(samples[k - 1]) - 2.0 * mean);
  }
  Vec3 u_mean = Vec3::Zero();
  for (const Vec3& v : u) u_mean += v;
  u_mean /= static_cast<double>(u.size());
  double max_abs = 0.0, sum_sq = 0.0;
  for (const Vec3& v : u) {
    max_abs = std::max(max_abs, (v - u_mean).cwiseAbs().maxCoeff());
    sum_sq += (v - u_mean).squaredNorm();
  }
  *excursion = max_abs;
  *rms = std::sqrt(sum_sq / static_cast<double>(u.size()));
}

/// Per-axis std of Hann means over kLowpassWindowNs, one every kLowpassHopNs.
void LowpassStd(std::span<const ImuSample> samples, Vec3* acc_std, Vec3* gyro_std) {
  const int64_t kLowpassWindowNs = SecToNs(kStillLowpassWindowS);
  constexpr int64_t kLowpassHopNs = 25'000'000;
  std::vector<Vec3> acc, gyro;
  size_t begin = 0;
  int64_t next_ns = samples.front().t_ns + kLowpassWindowNs;  // once 0.2 s is spanned
  for (size_t end = 1; end <= samples.size(); ++end) {
    const int64_t t_end = samples[end - 1].t_ns;
    if (t_end < next_ns) continue;
    while (t_end - samples[begin].t_ns > kLowpassWindowNs) ++begin;
    Vec3 a, g;
    HannMeans(samples.subspan(begin, end - begin), &a, &g);
    acc.push_back(a);
    gyro.push_back(g);
    next_ns = t_end + kLowpassHopNs;
  }
  *acc_std = Vec3::Zero();
  *gyro_std = Vec3::Zero();
  if (acc.size() < 2) return;
  auto axis_std = [](const std::vector<Vec3>& v) {
    Vec3 mean = Vec3::Zero(), sq = Vec3::Zero();
    for (const Vec3& x : v) mean += x;
    mean /= static_cast<double>(v.size());
    for (const Vec3& x : v) sq += (x - mean).cwiseAbs2();
    return Vec3((sq / static_cast<double>(v.size() - 1)).cwiseSqrt());
  };
  *acc_std = axis_std(acc);
  *gyro_std = axis_std(gyro);
}

}  // namespace

ImuStillness ComputeImuStillness(std::span<const ImuSample> samples) {
  ImuStillness s;
  if (samples.size() < 4) return s;
  HannMeans(samples, &s.acc_mean_mps2, &s.gyro_mean_radps);
  const size_t half = samples.size() / 2;
  HannMeans(samples.first(half), &s.acc_first_half_mps2, &s.gyro_first_half_radps);
  HannMeans(samples.subspan(half), &s.acc_second_half_mps2, &s.gyro_second_half_radps);
  double unused_rms = 0.0;
  Excursion(
      samples, s.acc_mean_mps2, [](const ImuSample& x) { return x.acc_mps2; },
      &s.velocity_excursion_mps, &s.velocity_rms_mps);
  Excursion(
      samples, s.gyro_mean_radps, [](const ImuSample& x) { return x.gyro_radps; },
      &s.angle_excursion_rad, &unused_rms);
  Vec3 acc_lowpass_std = Vec3::Zero();
  LowpassStd(samples, &acc_lowpass_std, &s.gyro_lowpass_std_axes_radps);
  s.acc_lowpass_std_mps2 = acc_lowpass_std.maxCoeff();
  s.gyro_lowpass_std_radps = s.gyro_lowpass_std_axes_radps.maxCoeff();
  s.acc_std_mps2 =
      ComputeImuMoments(samples, [](const ImuSample& x) { return x.acc_mps2; }).std.maxCoeff();
  s.gyro_std_radps =
      ComputeImuMoments(samples, [](const ImuSample& x) { return x.gyro_radps; }).std.maxCoeff();
  return s;
}

}  // namespace swlio::estimator

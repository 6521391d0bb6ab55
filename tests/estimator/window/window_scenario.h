#pragma once
/// @file
/// Test helper: a short sliding-window problem from simulated data. Frames every 0.1 s on the
/// "aggressive" route, IMU factors from the simulated (noisy, biased) IMU, and LiDAR factors
/// from points sampled on known world planes and lines, seen from the true poses with 2 cm
/// noise. Initial guesses are the truth perturbed (5 cm, 0.6°, 0.1 m/s; zero biases).

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <memory>
#include <random>
#include <vector>

#include "sim_imu_util.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/registration/point_to_line_factor.h"
#include "swlio/estimator/registration/point_to_plane_factor.h"

namespace swlio::test {

struct WindowScenario {
  std::vector<State> truth;
  std::vector<std::unique_ptr<estimator::ImuFactor>> imu;  ///< imu[k]: frame k → k + 1
  std::vector<std::vector<std::unique_ptr<ceres::CostFunction>>> lidar;  ///< per frame
  std::vector<double> extrinsic;                                         ///< T_imu_lidar, 7
  std::vector<std::vector<double>> pose_init, speed_bias_init;           ///< per frame
};

inline constexpr double kWindowPointSigmaM = 0.02;

inline WindowScenario MakeWindowScenario(int frames, uint32_t seed) {
  using Vec3 = Eigen::Vector3d;
  namespace est = estimator;
  WindowScenario s;
  std::optional<sim::SimSetup> setup = sim::MakeSimSetup("aggressive", 3, 14.0);
  const std::vector<ImuSample> imu =
      ToImuSamples(sim::SimulateImu(*setup->trajectory, setup->imu, 3));
  std::mt19937 rng(seed);
  std::normal_distribution<double> n01;
  auto gauss3 = [&](double sigma) -> Vec3 {
    Vec3 v;
    for (int i = 0; i < 3; ++i) v(i) = n01(rng) * sigma;  // sequenced: reproducible
    return v;
  };

  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  T_imu_lidar.linear() = lie::QuatFromRpy(0.01, -0.02, 1.57).toRotationMatrix();
  T_imu_lidar.translation() = Vec3(0.1, 0.0, 0.2);
  s.extrinsic.resize(est::kPoseSize);
  est::PoseToParameters(T_imu_lidar, s.extrinsic.data());

  const est::ImuNoiseConfig noise;
  for (int k = 0; k < frames; ++k) {
    s.truth.push_back(TrueState(*setup->trajectory, SecToNs(6.0 + 0.1 * k)));
  }
  for (int k = 0; k + 1 < frames; ++k) {
    est::Preintegrator pre(noise, Vec3::Zero(), Vec3::Zero());
    pre.Integrate(imu, s.truth[static_cast<size_t>(k)].t_ns,
                  s.truth[static_cast<size_t>(k) + 1].t_ns);
    s.imu.push_back(est::ImuFactor::Create(pre.result(), noise, 9.80665));
  }

  // Map planes (normal, point) and lines (direction, point) around the first position.
  const Vec3 p0 = s.truth[0].T_world_imu.translation();
  const std::vector<std::pair<Vec3, Vec3>> planes = {
      {Vec3(0, 0, 1), p0 + Vec3(0, 0, -1.5)},
      {Vec3(1, 0, 0), p0 + Vec3(6, 0, 0)},
      {Vec3(0, 1, 0), p0 + Vec3(0, -5, 0)},
      {Vec3(1, 1, 0).normalized(), p0 + Vec3(5, 5, 0)},
      {Vec3(-1, 0.3, 0.2).normalized(), p0 + Vec3(-7, 0, 0)},
      {Vec3(0.2, -1, 0.4).normalized(), p0 + Vec3(0, 8, 0)}};
  const std::vector<std::pair<Vec3, Vec3>> lines = {{Vec3(0, 0, 1), p0 + Vec3(3, 4, 0)},
                                                    {Vec3(0, 0, 1), p0 + Vec3(-4, 2, 0)},
                                                    {Vec3(1, 0, 0), p0 + Vec3(0, 3, 3)}};
  const double w = 1.0 / kWindowPointSigmaM;
  for (const State& t : s.truth) {
    const Eigen::Isometry3d T_lidar_world = (t.T_world_imu * T_imu_lidar).inverse();
    std::vector<std::unique_ptr<ceres::CostFunction>> factors;
    for (const auto& [n, c] : planes) {
      const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
      const Vec3 base = t.T_world_imu.translation() - n * n.dot(t.T_world_imu.translation() - c);
      for (int i = 0; i < 8; ++i) {
        const double u = 3.0 * n01(rng), v = 3.0 * n01(rng);
        const Vec3 x = base + u * e1 + v * e2 + gauss3(kWindowPointSigmaM);
        factors.push_back(est::PointToPlaneFactor::Create(T_lidar_world * x, n, c, w));
      }
    }
    for (const auto& [d, c] : lines) {
      for (int i = 0; i < 5; ++i) {
        const Vec3 x = c + 2.0 * n01(rng) * d + gauss3(kWindowPointSigmaM);
        factors.push_back(est::PointToLineFactor::Create(T_lidar_world * x, d, c, w));
      }
    }
    s.lidar.push_back(std::move(factors));

    Eigen::Isometry3d T0 = t.T_world_imu;
    T0.translation() += gauss3(0.05);
    T0.linear() = T0.linear() * lie::Exp(gauss3(0.01));
    std::vector<double> pose(est::kPoseSize), sb(est::kSpeedBiasSize, 0.0);
    est::PoseToParameters(T0, pose.data());
    Eigen::Map<Vec3>{sb.data() + est::kSbVel} = t.vel_world + gauss3(0.1);
    s.pose_init.push_back(pose);
    s.speed_bias_init.push_back(sb);
  }
  return s;
}

}  // namespace swlio::test

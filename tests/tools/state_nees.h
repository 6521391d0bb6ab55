#pragma once
// Normalized estimation error squared (NEES) of swlio-run's --covariance output against the
// simulator's ground truth, for the states the IMU and LiDAR observe in the window: the tilt
// against gravity (the attitude Q·R, Q the map's estimated tilt, identity unless estimated;
// rotation about the gravity-aligned x and y axes, 2 dof) and the velocity in the IMU frame
// (3 dof; Q does not change it).
// For a consistent estimator each averages its degrees of freedom over a run (Bar-Shalom, Li,
// Kirubarajan, "Estimation with Applications to Tracking and Navigation", §5.4). Position and
// yaw are left out: the window does not observe them absolutely (they drift with the map).

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "swlio/core/lie.h"
#include "swlio/estimator/window/state_covariance.h"
#include "swlio/eval/trajectory.h"

namespace swlio::test {

struct NeesSummary {
  size_t samples = 0;
  double tilt_mean = 0.0;      ///< expectation 2
  double velocity_mean = 0.0;  ///< expectation 3
};

struct CovarianceRow {
  double t_s = 0.0;
  Eigen::Matrix3d R_world_imu;
  Eigen::Vector3d vel_world;
  estimator::StateCovarianceMatrix P;
  Eigen::Matrix3d R_gravity_imu;  ///< Q·R: the attitude against gravity
  Eigen::Matrix3d P_rot_gravity;  ///< its covariance (StateCovariance::rot_gravity)
};

inline constexpr size_t kCovarianceCsvColumns = 11 + 120 + 2 + 6;

inline std::vector<CovarianceRow> ReadCovarianceCsv(const std::filesystem::path& path) {
  std::vector<CovarianceRow> rows;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) v.push_back(std::stod(field));
    if (v.size() != kCovarianceCsvColumns) continue;
    CovarianceRow r;
    r.t_s = v[0] * 1e-9;
    r.R_world_imu = Eigen::Quaterniond(v[7], v[4], v[5], v[6]).normalized().toRotationMatrix();
    r.vel_world = Eigen::Vector3d(v[8], v[9], v[10]);
    size_t k = 11;
    for (int i = 0; i < 15; ++i) {
      for (int j = i; j < 15; ++j) r.P(i, j) = r.P(j, i) = v[k++];
    }
    const Eigen::Vector3d tilt(v[k], v[k + 1], 0.0);
    k += 2;
    r.R_gravity_imu = lie::Exp(tilt) * r.R_world_imu;
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) r.P_rot_gravity(i, j) = r.P_rot_gravity(j, i) = v[k++];
    }
    rows.push_back(r);
  }
  return rows;
}

/// Samples of the first `skip_s` seconds (initialization transient) are left out.
inline NeesSummary StateNees(const std::filesystem::path& groundtruth_tum,
                             const std::filesystem::path& covariance_csv,
                             double skip_s) {
  const eval::Trajectory gt = eval::ReadTumFile(groundtruth_tum);
  const std::vector<CovarianceRow> rows = ReadCovarianceCsv(covariance_csv);
  NeesSummary out;
  if (rows.empty() || gt.Size() < 3) return out;
  const std::vector<double>& t = gt.stamps_s;
  auto rotation = [&](size_t i) { return Eigen::Matrix3d(gt.poses[i].block<3, 3>(0, 0)); };
  auto velocity = [&](size_t i) {  // central difference
    return Eigen::Vector3d((gt.Position(i + 1) - gt.Position(i - 1)) / (t[i + 1] - t[i - 1]));
  };
  Eigen::Matrix3d R_yaw;  // the estimate's world in the truth's: a yaw about the vertical
  bool aligned = false;
  for (const CovarianceRow& r : rows) {
    const size_t i = static_cast<size_t>(std::lower_bound(t.begin(), t.end(), r.t_s) - t.begin());
    if (i < 1 || i + 1 >= t.size()) continue;
    const size_t n = (r.t_s - t[i - 1] < t[i] - r.t_s) ? i - 1 : i;
    if (n < 1 || n + 1 >= t.size()) continue;
    if (!aligned) {
      const double yaw = lie::Log(Eigen::Matrix3d(r.R_gravity_imu * rotation(n).transpose())).z();
      R_yaw = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      aligned = true;
    }
    if (r.t_s < rows.front().t_s + skip_s) continue;
    const Eigen::Matrix3d R_true = R_yaw * rotation(n);
    const Eigen::Vector3d e_rot = lie::Log(Eigen::Matrix3d(r.R_gravity_imu * R_true.transpose()));
    const Eigen::Vector2d e_tilt = e_rot.head<2>();
    const Eigen::Matrix2d P_tilt = r.P_rot_gravity.topLeftCorner<2, 2>();
    const Eigen::Vector3d e_vel =
        r.R_world_imu.transpose() * r.vel_world - rotation(n).transpose() * velocity(n);
    const Eigen::Matrix3d P_vel = estimator::VelocityImuCovariance(r.P, r.R_world_imu, r.vel_world);
    out.tilt_mean += e_tilt.dot(P_tilt.ldlt().solve(e_tilt));
    out.velocity_mean += e_vel.dot(P_vel.ldlt().solve(e_vel));
    ++out.samples;
  }
  if (out.samples > 0) {
    out.tilt_mean /= static_cast<double>(out.samples);
    out.velocity_mean /= static_cast<double>(out.samples);
  }
  return out;
}

}  // namespace swlio::test

#pragma once
// One frame of the window (private to the WindowEstimator sources): its parameter blocks, its
// features, its linearized LiDAR rows and the IMU factor from the previous frame.

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "swlio/estimator/common/pose_manifold.h"
#include "swlio/estimator/imu/gravity_tilt_imu_factor.h"
#include "swlio/estimator/imu/imu_factor.h"
#include "swlio/estimator/imu/preintegration.h"
#include "swlio/estimator/imu/time_shift_jacobian.h"
#include "swlio/estimator/registration/neighbour_cache.h"
#include "swlio/estimator/wheel/wheel_velocity_factor.h"
#include "swlio/estimator/window/marginalization_prior.h"
#include "swlio/estimator/window/standstill.h"
#include "swlio/estimator/window/window_estimator.h"

namespace swlio::estimator {

struct WindowEstimator::Frame {
  int64_t t_ns = 0;
  std::array<double, kPoseSize> pose{};
  std::array<double, kSpeedBiasSize> speed_bias{};
  std::vector<Eigen::Vector3d> planes_lidar, edges_lidar;
  NeighbourCache neighbours;  ///< the features' map searches, from one association to the next
  /// Its point-to-plane/line factors against the local map, linearized at the newest-frame
  /// registration (≤ 6 rows, or ≤ 12 with the extrinsic); null without LiDAR information.
  std::unique_ptr<MarginalizationPrior> lidar_linear;
  Eigen::Isometry3d T_linearized = Eigen::Isometry3d::Identity();  ///< pose of lidar_linear
  size_t plane_factors = 0, line_factors = 0;
  std::unique_ptr<Preintegrator> pre;  ///< previous frame → this one
  /// How `pre` moves with an error of the applied LiDAR–IMU time offset, and that offset's σ
  /// when the samples were shifted (time_shift_jacobian.h).
  Vec9 pre_time_shift_jacobian = Vec9::Zero();
  double pre_offset_sigma_s = 0.0;
  std::unique_ptr<ImuFactor> imu;  ///< null for the first frame (or a failed interval)
  std::unique_ptr<GravityTiltImuFactor> imu_tilt;     ///< `imu` in the map frame (estimated tilt)
  std::unique_ptr<WheelVelocityFactor> wheel;         ///< null without a wheel measurement
  std::unique_ptr<ZeroVelocityFactor> zero_velocity;  ///< null unless at rest (standstill.h)

  /// The IMU factor from `pre`, its covariance widened by the time offset's uncertainty.
  void MakeImu(const ImuNoiseConfig& noise, double gravity_mps2) {
    SetImu(ImuFactor::Create(
        WithTimeOffsetUncertainty(pre->result(), pre_time_shift_jacobian, pre_offset_sigma_s),
        noise, gravity_mps2));
  }

  void SetImu(std::unique_ptr<ImuFactor> factor) {
    imu = std::move(factor);
    imu_tilt = imu != nullptr ? std::make_unique<GravityTiltImuFactor>(imu.get()) : nullptr;
  }

  Eigen::Vector3d BiasAcc() const { return Eigen::Map<const Eigen::Vector3d>(&speed_bias[3]); }
  Eigen::Vector3d BiasGyro() const { return Eigen::Map<const Eigen::Vector3d>(&speed_bias[6]); }
};

}  // namespace swlio::estimator

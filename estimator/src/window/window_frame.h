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
#include "swlio/estimator/imu/time_offset_imu_factor.h"
#include "swlio/estimator/imu/time_shift_jacobian.h"
#include "swlio/estimator/registration/neighbour_cache.h"
#include "swlio/estimator/wheel/wheel_velocity_factor.h"
#include "swlio/estimator/window/marginalization_prior.h"
#include "swlio/estimator/window/standstill.h"
#include "swlio/estimator/window/window_estimator.h"

namespace swlio::estimator {

/// How a frame's IMU factor is made from its pre-integration.
struct WindowEstimator::FrameImuOptions {
  ImuNoiseConfig noise;
  double gravity_mps2 = 0.0;
  bool gravity_tilt = false;   ///< the map's tilt is a parameter (imu_tilt)
  bool window_offset = false;  ///< the time offset is a parameter (imu_offset)
};

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
  /// How `pre` moves with an error of the LiDAR–IMU time offset, the offset its samples were
  /// shifted with, and that offset's σ then (time_shift_jacobian.h).
  Vec9 pre_time_shift_jacobian = Vec9::Zero();
  double pre_applied_offset_s = 0.0;
  double pre_offset_sigma_s = 0.0;
  std::unique_ptr<ImuFactor> imu;  ///< null for the first frame (or a failed interval)
  std::unique_ptr<GravityTiltImuFactor> imu_tilt;  ///< `imu` in the map frame (estimated tilt)
  /// `imu` or `imu_tilt` with the window's time offset (time_offset_imu_factor.h); null unless
  /// the window estimates the offset.
  std::unique_ptr<TimeOffsetImuFactor> imu_offset;
  std::unique_ptr<WheelVelocityFactor> wheel;         ///< null without a wheel measurement
  std::unique_ptr<ZeroVelocityFactor> zero_velocity;  ///< null unless at rest (standstill.h)

  /// The IMU factor from `pre`, its covariance widened by the time offset's uncertainty (if
  /// any), and with the window's offset block where that is free.
  void MakeImu(const FrameImuOptions& o) {
    imu = ImuFactor::Create(
        WithTimeOffsetUncertainty(pre->result(), pre_time_shift_jacobian, pre_offset_sigma_s),
        o.noise, o.gravity_mps2);
    imu_tilt = imu != nullptr ? std::make_unique<GravityTiltImuFactor>(imu.get()) : nullptr;
    imu_offset.reset();
    if (imu == nullptr || !o.window_offset) return;
    const ceres::CostFunction* inner =
        o.gravity_tilt ? static_cast<const ceres::CostFunction*>(imu_tilt.get()) : imu.get();
    imu_offset = std::make_unique<TimeOffsetImuFactor>(inner, *imu, pre_time_shift_jacobian,
                                                       pre_applied_offset_s);
  }

  /// The cost function the window adds between the previous frame and this one.
  ceres::CostFunction* ImuCost(bool gravity_tilt) {
    if (imu_offset != nullptr) return imu_offset.get();
    if (gravity_tilt) return imu_tilt.get();
    return imu.get();
  }

  void ResetImu() {
    imu_offset.reset();
    imu_tilt.reset();
    imu.reset();
  }

  Eigen::Vector3d BiasAcc() const { return Eigen::Map<const Eigen::Vector3d>(&speed_bias[3]); }
  Eigen::Vector3d BiasGyro() const { return Eigen::Map<const Eigen::Vector3d>(&speed_bias[6]); }
};

}  // namespace swlio::estimator

#pragma once
/// @file
/// What the daemon's threads hand each other through their SPSC queues. Fixed-size values
/// only, so a full queue never allocates and a queue slot is reused as is — except the
/// keyframes for loop closure (a shared pointer: the optimizer allocates one per keyframe,
/// about five a second, off the rx threads).

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/estimator/common/keyframe_cloud.h"
#include "swlio/estimator/registration/lidar_odometry.h"
#include "swlio/estimator/window/state_covariance.h"
#include "swlio/ipc/messages.h"

namespace swlio::daemon {

/// One UDP datagram from the LiDAR as the lidar_rx thread received it.
struct LidarPacket {
  static constexpr size_t kMaxBytes = 1280;  ///< RS16 MSOP/DIFOP 1248, VLP-16 1206
  std::array<uint8_t, kMaxBytes> bytes{};
  uint16_t size = 0;
  bool difop = false;   ///< received on the DIFOP port (else MSOP)
  int64_t t_rx_ns = 0;  ///< host receive time, CLOCK_MONOTONIC
};

/// Serial bytes as the imu_rx thread read them: one read(2), or a piece of a longer one (each
/// piece with the read's time).
struct SerialChunk {
  static constexpr size_t kMaxBytes = 1024;
  std::array<uint8_t, kMaxBytes> bytes{};
  uint16_t size = 0;
  /// The serial port's open number (XsensSerialDriver::epoch): where it changes, the device was
  /// opened again and a new byte stream begins.
  uint32_t epoch = 0;
  int64_t t_rx_ns = 0;  ///< host time of the read, CLOCK_MONOTONIC
};

/// Estimator state of health (published, logged, and the READY=1 condition).
enum class TrackingState : uint8_t { kInitializing, kTracking, kDegraded, kLost };
const char* ToString(TrackingState state);

/// The optimizer's result for one sweep, to the propagator and the publisher.
struct SweepEstimate {
  State state;  ///< at the sweep's end, host time
  estimator::StateCovariance covariance;
  estimator::OdometryStatus status = estimator::OdometryStatus::kInitializing;
  TrackingState tracking = TrackingState::kInitializing;
  int degenerate_directions = 0;
  double update_ms = 0.0;       ///< the whole update (front end + window), thread CPU
  int64_t scan_last_rx_ns = 0;  ///< host receive time of the sweep's last packet
  /// The LiDAR–IMU time offset the estimator applies to the IMU samples (a sample stamped t
  /// measured the motion of t − offset): the IMU-rate output applies it too.
  int64_t imu_time_offset_ns = 0;
  /// The LiDAR–IMU extrinsic the estimator used for this sweep (refined online when
  /// configured): /tf_static follows it. Meaningless unless has_extrinsic.
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  bool keyframe = false;  ///< the sweep's features went into the local map
  bool has_extrinsic = false;
  /// The estimator re-initialized (its state diverged): the IMU-rate output must stop
  /// propagating the old state until the next estimate.
  bool reset = false;
};

/// A keyframe of the window (pose, features), from the optimizer to the loop-closure thread.
using KeyframePtr = std::shared_ptr<const estimator::KeyframeCloud>;

/// A new map correction from the loop-closure thread to the publisher, which follows it at a
/// bounded rate (estimator/loop/correction_slew.h).
struct MapCorrection {
  int64_t t_ns = 0;  ///< sweep end of the keyframe whose loop produced it (daemon time)
  Eigen::Isometry3d T_map_odom = Eigen::Isometry3d::Identity();
  /// The graph's nodes at their corrected poses (daemon time): the published keyframe path
  /// is replaced by it. Allocated by the loop-closure thread once per accepted loop.
  std::shared_ptr<const std::vector<estimator::MapNode>> path;
  /// Take the correction at once instead of following it: the first pose in a saved map
  /// (nothing was published before it).
  bool jump = false;
};

/// One IMU-rate output, from the propagator to the publisher.
struct ImuRatePose {
  State state;
  Eigen::Vector3d gyro_imu_radps = Eigen::Vector3d::Zero();
  int64_t since_optimized_ns = 0;
  int64_t rx_ns = 0;                   ///< host receive time of the IMU frame it came from
  ipc::Covariance6 pose_covariance{};  ///< ROS order (message_conversion.h); zeros if unknown
};

}  // namespace swlio::daemon

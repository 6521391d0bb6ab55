#pragma once
/// @file
/// The current sweep for viewers (ipc.sweep_topic; issue 34): after each tracked sweep the
/// optimizer thread hands over the estimator's de-skewed sweep (every point in the LiDAR frame
/// at the sweep's end) and the odometry pose it registered; this writes it as
/// sensor_msgs/PointCloud2 (x, y, z, intensity) in the map frame, placed with the correction the
/// publisher thread applies now (correction_cell.h), stamped at the sweep's end in the published
/// stamps' clock. Until the publisher has a correction (localizing: the first relocalization)
/// sweeps are held back and counted. The message buffer is reused: no allocation once it has
/// held the largest sweep.

#include <Eigen/Geometry>
#include <atomic>
#include <cstdint>
#include <string>

#include "swlio/core/types.h"
#include "swlio/daemon/output/correction_cell.h"
#include "swlio/daemon/output/stamp_clock.h"
#include "swlio/ipc/messages.h"

namespace swlio::ipc {
class Publisher;
}

namespace swlio::daemon {

struct SweepPublishCounters {
  bool enabled = false;
  uint64_t published = 0;
  uint64_t failures = 0;
  uint64_t held = 0;     ///< not published: no map correction yet
  double last_ms = 0.0;  ///< conversion and write of the last sweep (thread time of the caller)
};

class SweepPublisher {
 public:
  /// `publisher` must outlive this (null: counts, writes nothing).
  SweepPublisher(ipc::Publisher* publisher, std::string frame_id);
  /// The published stamps' clock (null: host time).
  void StampWith(const StampClock* stamps) { stamps_ = stamps; }
  /// The correction into the map frame (null: the points stay in the frame given).
  void CorrectWith(const CorrectionCell* correction) { correction_ = correction; }
  /// `deskewed` in the LiDAR frame at host time `t_host_ns`, where the LiDAR is at T_odom_lidar.
  bool Publish(const Scan& deskewed, const Eigen::Isometry3d& T_odom_lidar, int64_t t_host_ns);
  SweepPublishCounters counters() const;

 private:
  ipc::Publisher* publisher_;
  const StampClock* stamps_ = nullptr;
  const CorrectionCell* correction_ = nullptr;
  ipc::PointCloud2 msg_;
  std::atomic<uint64_t> published_{0}, failures_{0}, held_{0};
  std::atomic<double> last_ms_{0.0};
};

}  // namespace swlio::daemon

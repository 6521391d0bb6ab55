#include "swlio/daemon/output/sweep_publisher.h"

#include <utility>

#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/ipc/point_cloud.h"
#include "swlio/ipc/publisher.h"

namespace swlio::daemon {

SweepPublisher::SweepPublisher(ipc::Publisher* publisher, std::string frame_id)
    : publisher_(publisher) {
  msg_.frame_id = std::move(frame_id);
}

bool SweepPublisher::Publish(const Scan& deskewed,
                             const Eigen::Isometry3d& T_odom_lidar,
                             int64_t t_host_ns) {
  const int64_t t0 = ThreadCpuNowNs();
  Eigen::Isometry3d T_map_odom = Eigen::Isometry3d::Identity();
  if (correction_ != nullptr && !correction_->Load(&T_map_odom)) {
    held_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  const Eigen::Isometry3d T_frame_lidar = T_map_odom * T_odom_lidar;
  const size_t n = deskewed.points.size();
  bool ok = ipc::InitXyzCloud(n, /*with_intensity=*/true, &msg_);
  if (ok) {
    msg_.t_ns = stamps_ != nullptr ? stamps_->ToStamp(t_host_ns) : t_host_ns;
    const Eigen::Matrix3f R = T_frame_lidar.linear().cast<float>();
    const Eigen::Vector3f t = T_frame_lidar.translation().cast<float>();
    for (size_t i = 0; i < n; ++i) {
      const LidarPoint& p = deskewed.points[i];
      const Eigen::Vector3f q = R * p.xyz_m + t;
      ipc::SetPoint(i, {q.x(), q.y(), q.z()}, p.intensity, &msg_);
    }
    ok = publisher_ == nullptr || publisher_->PublishSweep(msg_);
  }
  (ok ? published_ : failures_).fetch_add(1, std::memory_order_relaxed);
  last_ms_.store(static_cast<double>(ThreadCpuNowNs() - t0) * 1e-6, std::memory_order_relaxed);
  return ok;
}

SweepPublishCounters SweepPublisher::counters() const {
  SweepPublishCounters c;
  c.enabled = true;
  c.published = published_.load(std::memory_order_relaxed);
  c.failures = failures_.load(std::memory_order_relaxed);
  c.held = held_.load(std::memory_order_relaxed);
  c.last_ms = last_ms_.load(std::memory_order_relaxed);
  return c;
}

}  // namespace swlio::daemon

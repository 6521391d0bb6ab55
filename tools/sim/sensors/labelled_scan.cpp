#include "sensors/labelled_scan.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "swlio/core/time.h"

namespace swlio::sim {

LabelledScanSource::LabelledScanSource(const SimSetup& setup)
    : setup_(&setup),
      lidar_(setup.world.get(), setup.trajectory.get(), setup.lidar, setup.seed),
      period_ns_(SecToNs(60.0 / setup.lidar.rpm)) {
  // Ring = rank of the channel's vertical angle (0 = lowest).
  const auto& angles = setup.lidar.vertical_angles_deg;
  std::vector<size_t> order(angles.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return angles[a] < angles[b]; });
  ring_of_channel_.resize(angles.size());
  for (size_t rank = 0; rank < order.size(); ++rank) {
    ring_of_channel_[order[rank]] = static_cast<uint16_t>(rank);
  }
}

Eigen::Isometry3d LabelledScanSource::LidarPose(double t_s) const {
  const Kinematics k = setup_->trajectory->At(t_s);
  Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
  T_world_imu.linear() = k.R_world_body;
  T_world_imu.translation() = k.p_world;
  return T_world_imu * setup_->lidar.T_imu_lidar;
}

bool LabelledScanSource::Next(LabelledScan* out, double t_min_s) {
  const int64_t t_min_ns = SecToNs(t_min_s);
  while (!done_) {
    const int64_t start_ns = next_start_ns_;
    const int64_t end_ns = start_ns + period_ns_;
    // Gather every return of [start, end): pending ones first, then new packets.
    std::vector<SimReturn> sweep;
    std::swap(sweep, pending_);
    while (sweep.empty() || sweep.back().t_true_ns < end_ns) {
      SimPacket packet;
      if (!lidar_.Next(&packet, &packet_)) {
        done_ = true;
        break;
      }
      sweep.insert(sweep.end(), packet_.begin(), packet_.end());
    }
    const auto split = std::partition_point(
        sweep.begin(), sweep.end(), [&](const SimReturn& r) { return r.t_true_ns < end_ns; });
    pending_.assign(split, sweep.end());
    sweep.erase(split, sweep.end());
    next_start_ns_ = end_ns;
    if (done_ || start_ns < t_min_ns) continue;

    out->scan = Scan{};
    out->scan.t_start_ns = start_ns;
    out->scan.t_end_ns = sweep.empty() ? start_ns : sweep.back().t_true_ns;
    out->cls.clear();
    out->moving.clear();
    out->p_world.clear();
    out->T_world_lidar_end = LidarPose(NsToSec(out->scan.t_end_ns));
    const Eigen::Isometry3d T_end_world = out->T_world_lidar_end.inverse();
    Eigen::Isometry3d T_end_fire = Eigen::Isometry3d::Identity();
    int64_t pose_t_ns = -1;
    for (const SimReturn& r : sweep) {
      if (r.range_m <= 0.0) continue;
      const double t_s = NsToSec(r.t_true_ns);
      if (r.t_true_ns - pose_t_ns > 50'000) {  // one pose per firing sequence (55.5 µs)
        T_end_fire = T_end_world * LidarPose(t_s);
        pose_t_ns = r.t_true_ns;
      }
      LidarPoint p;  // where the decoder puts it (lens centre + range along the ray)
      p.xyz_m = (T_end_fire * SimDecodedPoint(setup_->lidar, r.channel, r.t_true_ns, r.range_m))
                    .cast<float>();
      p.ring = ring_of_channel_[r.channel];
      p.dt_ns = r.t_true_ns - start_ns;
      out->scan.points.push_back(p);
      out->cls.push_back(r.cls);
      out->moving.push_back(r.moving ? 1 : 0);
      out->p_world.push_back(r.p_world);
    }
    return true;
  }
  return false;
}

}  // namespace swlio::sim

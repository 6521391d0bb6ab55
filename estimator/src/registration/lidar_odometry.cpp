#include "swlio/estimator/registration/lidar_odometry.h"

#include "swlio/core/time.h"
#include "swlio/estimator/frontend/deskew.h"

namespace swlio::estimator {
namespace {

void ToVectors(const std::vector<FeaturePoint>& in, std::vector<Eigen::Vector3d>* out) {
  out->clear();
  for (const FeaturePoint& f : in) out->push_back(f.xyz_m.cast<double>());
}

}  // namespace

LidarOdometryConfig MakeOdometryConfig(const EstimatorConfig& estimator,
                                       const Eigen::Isometry3d& T_imu_lidar) {
  LidarOdometryConfig c;
  c.estimator = estimator;
  c.T_imu_lidar = T_imu_lidar;
  c.front_end.plane_voxel_m = estimator.plane_voxel_m;
  c.front_end.edge_voxel_m = estimator.edge_voxel_m;
  c.plane_map.radius_m = estimator.local_map_radius_m;
  c.edge_map.radius_m = estimator.local_map_radius_m;
  return c;
}

ConfigIssues LidarOdometryConfig::Validate() const {
  ConfigIssues issues;
  AppendWithPrefix(issues, "estimator", estimator.Validate());
  AppendWithPrefix(issues, "front_end", front_end.Validate());
  AppendWithPrefix(issues, "matcher", matcher.Validate());
  AppendWithPrefix(issues, "plane_map", plane_map.Validate());
  AppendWithPrefix(issues, "edge_map", edge_map.Validate());
  CheckInRange<size_t>(issues, "min_inliers", min_inliers, 6, 100000);
  CheckInRange(issues, "keyframe_distance_m", keyframe_distance_m, 0.0, 10.0);
  CheckInRange(issues, "keyframe_angle_rad", keyframe_angle_rad, 0.0, 1.0);
  return issues;
}

const char* ToString(OdometryStatus status) {
  switch (status) {
    case OdometryStatus::kInitializing:
      return "initializing";
    case OdometryStatus::kTracking:
      return "tracking";
    case OdometryStatus::kMatchFailed:
      return "match_failed";
    case OdometryStatus::kSkipped:
      return "skipped";
  }
  return "unknown";
}

LidarOdometry::LidarOdometry(const LidarOdometryConfig& config, NowNsFn now_ns)
    : config_(config),
      now_ns_(now_ns),
      initializer_(config.estimator),
      propagator_(config.estimator.gravity_mps2),
      front_end_(config.front_end),
      plane_map_(config.plane_map),
      edge_map_(config.edge_map),
      matcher_(config.matcher) {}

void LidarOdometry::AddImu(const ImuSample& sample) {
  if (initialized_) {
    pending_imu_.push_back(sample);
    return;
  }
  if (initializer_.Add(sample).status == InitStatus::kInitialized) {
    initialized_ = true;
    propagator_.Reset(initializer_.result().state);
    propagator_.Add(sample);
  }
}

void LidarOdometry::PropagateTo(int64_t t_ns) {
  while (!pending_imu_.empty() && pending_imu_.front().t_ns <= t_ns) {
    propagator_.Add(pending_imu_.front());
    pending_imu_.pop_front();
  }
  propagator_.ExtrapolateTo(t_ns);
}

OdometryResult LidarOdometry::AddScan(const Scan& scan) {
  StageTimer timer(now_ns_);
  OdometryResult result;
  result.points_in = scan.points.size();
  if (!initialized_) return result;
  if (scan.t_start_ns < propagator_.state().t_ns) {
    result.status = OdometryStatus::kSkipped;
    return result;
  }

  PropagateTo(scan.t_end_ns);
  const DeskewResult deskew = Deskew(scan, propagator_.track(), config_.T_imu_lidar, &xyz_);
  result.points_uncovered = deskew.uncovered;
  deskewed_ = scan;
  for (size_t i = 0; i < xyz_.size(); ++i) deskewed_.points[i].xyz_m = xyz_[i].cast<float>();
  front_end_.Process(deskewed_, &features_);
  ToVectors(features_.features.planes, &planes_lidar_);
  ToVectors(features_.features.edges, &edges_lidar_);
  result.planes = planes_lidar_.size();
  result.edges = edges_lidar_.size();
  result.times.frontend_ms = timer.Lap();

  Eigen::Isometry3d T_world_lidar = propagator_.state().T_world_imu * config_.T_imu_lidar;
  result.status = OdometryStatus::kTracking;
  if (plane_map_.size() > 0) {
    result.match =
        matcher_.Match(planes_lidar_, edges_lidar_, plane_map_, edge_map_, T_world_lidar);
    if (result.match.plane_inliers + result.match.edge_inliers >= config_.min_inliers) {
      T_world_lidar = result.match.T_world_lidar;
    } else {
      result.status = OdometryStatus::kMatchFailed;  // keep the IMU prediction
    }
    result.times.match_ms = timer.Lap();
  }
  Correct(T_world_lidar, scan.t_end_ns);
  result.keyframe = IsKeyframe(T_world_lidar);
  if (result.keyframe) InsertFeatures(T_world_lidar);
  result.state = propagator_.state();
  result.times.total_ms = result.times.frontend_ms + result.times.match_ms + timer.Lap();
  return result;
}

void LidarOdometry::Correct(const Eigen::Isometry3d& T_world_lidar, int64_t t_ns) {
  State corrected = propagator_.state();
  const Eigen::Isometry3d T_world_imu = T_world_lidar * config_.T_imu_lidar.inverse();
  const int64_t period_ns = t_ns - propagator_.track().begin_ns();
  if (period_ns > 0) {
    corrected.vel_world +=
        (T_world_imu.translation() - corrected.T_world_imu.translation()) / NsToSec(period_ns);
  }
  corrected.T_world_imu = T_world_imu;
  corrected.t_ns = t_ns;
  propagator_.Reset(corrected);
}

bool LidarOdometry::IsKeyframe(const Eigen::Isometry3d& T_world_lidar) const {
  if (!have_keyframe_) return true;
  const Eigen::Isometry3d moved = T_world_last_keyframe_.inverse() * T_world_lidar;
  return moved.translation().norm() >= config_.keyframe_distance_m ||
         Eigen::AngleAxisd(moved.linear()).angle() >= config_.keyframe_angle_rad;
}

void LidarOdometry::InsertFeatures(const Eigen::Isometry3d& T_world_lidar) {
  have_keyframe_ = true;
  T_world_last_keyframe_ = T_world_lidar;
  for (Eigen::Vector3d& p : planes_lidar_) p = T_world_lidar * p;
  for (Eigen::Vector3d& p : edges_lidar_) p = T_world_lidar * p;
  plane_map_.Insert(planes_lidar_);
  edge_map_.Insert(edges_lidar_);
  plane_map_.RemoveFar(T_world_lidar.translation());
  edge_map_.RemoveFar(T_world_lidar.translation());
}

}  // namespace swlio::estimator

#include "loop_closure_run.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>

#include "spread.h"
#include "swlio/daemon/output/tum_output.h"

namespace swlio::tools {

LoopClosureRun::LoopClosureRun(const estimator::LoopClosureConfig& config,
                               estimator::NowNsFn now_ns,
                               daemon::TimeScale time)
    : closure_(config), now_ns_(now_ns), time_(time) {}

State LoopClosureRun::OnSweep(const State& odom, const estimator::KeyframeCloud* keyframe) {
  sweeps_.push_back(odom);
  if (keyframe != nullptr) {
    const int64_t t0 = now_ns_ != nullptr ? now_ns_() : 0;
    const estimator::LoopClosureUpdate u = closure_.AddKeyframe(*keyframe);
    const double ms = now_ns_ != nullptr ? static_cast<double>(now_ns_() - t0) * 1e-6 : 0.0;
    if (u.attempted) update_ms_.push_back(ms);
    if (u.optimized) graph_ms_.push_back(ms);
  }
  State out = odom;
  out.T_world_imu = closure_.T_map_odom() * odom.T_world_imu;
  out.vel_world = closure_.T_map_odom().linear() * odom.vel_world;
  return out;
}

void LoopClosureRun::OnGnss(const GnssFix& fix) {
  const int64_t t0 = now_ns_ != nullptr ? now_ns_() : 0;
  const estimator::LoopClosureUpdate u = closure_.AddGnss(fix);
  if (u.optimized && now_ns_ != nullptr) {
    gnss_ms_.push_back(static_cast<double>(now_ns_() - t0) * 1e-6);
  }
}

bool LoopClosureRun::WriteEnu(const std::string& path, std::string* error) const {
  const std::optional<Eigen::Isometry3d> T_enu_map = closure_.T_enu_map();
  if (!T_enu_map) {
    *error = "no GNSS alignment (too few fixes, or they never spanned align_min_distance_m)";
    return false;
  }
  std::ofstream out(path);
  if (!out) {
    *error = "cannot write " + path;
    return false;
  }
  const std::optional<Geodetic> o = closure_.enu_origin();
  char header[256];
  std::snprintf(header, sizeof header,
                "# timestamp tx ty tz qx qy qz qw  (IMU frame in the local ENU frame at lat %.8f "
                "lon %.8f h %.3f; final pose graph)\n",
                o ? o->lat_deg : 0.0, o ? o->lon_deg : 0.0, o ? o->height_m : 0.0);
  out << header;
  for (State s : sweeps_) {
    s.T_world_imu = *T_enu_map * closure_.CorrectedPose(s.t_ns, s.T_world_imu);
    s.t_ns = time_.ToHost(s.t_ns);
    daemon::WriteTumLine(out, s);
  }
  if (!out) *error = "cannot write " + path;
  return static_cast<bool>(out);
}

bool LoopClosureRun::WriteOptimized(const std::string& path) const {
  std::ofstream out(path);
  if (!out) return false;
  out << "# timestamp tx ty tz qx qy qz qw  (IMU frame, host time, sweep end; final pose graph)\n";
  for (State s : sweeps_) {
    s.T_world_imu = closure_.CorrectedPose(s.t_ns, s.T_world_imu);
    s.t_ns = time_.ToHost(s.t_ns);
    daemon::WriteTumLine(out, s);
  }
  return static_cast<bool>(out);
}

bool LoopClosureRun::WritePath(const std::string& path) const {
  std::ofstream out(path);
  if (!out) return false;
  out << "# timestamp tx ty tz qx qy qz qw  (IMU frame, host time; the final pose graph's nodes)\n";
  for (const estimator::MapNode& node : closure_.MapPath()) {
    State s;
    s.t_ns = time_.ToHost(node.t_ns);
    s.T_world_imu = node.T_map_imu;
    daemon::WriteTumLine(out, s);
  }
  return static_cast<bool>(out);
}

bool LoopClosureRun::WriteLoops(const std::string& path) const {
  std::ofstream out(path);
  if (!out) return false;
  out << "candidate_t_ns,node_t_ns,distance_m,verdict,fitness,inliers,min_eigenvalue,"
         "correction_m,correction_rad,x,y,z,qx,qy,qz,qw,source\n";
  for (const estimator::LoopAttempt& a : closure_.attempts()) {
    const Eigen::Isometry3d T =
        a.check.T_candidate_lidar * closure_.node(a.node).T_imu_lidar.inverse();
    const Eigen::Quaterniond q(T.rotation());
    char line[512];
    std::snprintf(
        line, sizeof line,
        "%lld,%lld,%.3f,%s,%.3f,%zu,%.2f,%.4f,%.5f,%.4f,%.4f,%.4f,%.6f,%.6f,%.6f,%.6f,%s\n",
        static_cast<long long>(time_.ToHost(closure_.node(a.candidate).t_ns)),
        static_cast<long long>(time_.ToHost(closure_.node(a.node).t_ns)), a.distance_m,
        estimator::ToString(a.check.verdict), a.check.fitness, a.check.inliers,
        a.check.min_eigenvalue, a.check.correction_m, a.check.correction_rad, T.translation().x(),
        T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w(),
        a.by_descriptor ? "descriptor" : "radius");
    out << line;
  }
  return static_cast<bool>(out);
}

size_t LoopClosureRun::ByDescriptor() const {
  size_t n = 0;
  for (const estimator::LoopAttempt& a : closure_.attempts()) {
    n += a.by_descriptor && a.check.verdict == estimator::LoopVerdict::kAccepted ? 1 : 0;
  }
  return n;
}

bool LoopClosureRun::SaveMap(const std::string& path,
                             const std::string& pcd_path,
                             std::string* error) const {
  const estimator::SavedMap map = closure_.ToSavedMap();
  if (!estimator::SaveMapFile(path, map, error)) return false;
  return pcd_path.empty() ||
         estimator::SaveMergedPcd(pcd_path, map, estimator::kMergedCloudVoxelM, error);
}

std::string LoopClosureRun::SummaryJson() const {
  const estimator::LoopClosureStats& s = closure_.stats();
  const auto verify = Spread(update_ms_);
  const auto graph = Spread(graph_ms_);
  char json[512];
  std::snprintf(json, sizeof json,
                "\"loops\": {\"nodes\": %zu, \"attempts\": %zu, \"accepted\": %zu, "
                "\"rejected\": %zu, \"by_descriptor\": %zu, \"attempt_ms\": [%.2f, %.2f, %.2f], "
                "\"accepted_ms\": [%.2f, %.2f, %.2f]}",
                s.nodes, s.attempts, s.accepted, s.rejected, ByDescriptor(), verify[0], verify[1],
                verify[2], graph[0], graph[1], graph[2]);
  std::string out = json;
  if (s.gnss.fixes == 0) return out;
  const auto gnss = Spread(gnss_ms_);
  const std::optional<Eigen::Isometry3d> T = closure_.T_enu_map();
  const double yaw = T ? std::atan2(T->linear()(1, 0), T->linear()(0, 0)) : 0.0;
  std::snprintf(json, sizeof json,
                ", \"gnss\": {\"fixes\": %zu, \"bad_quality\": %zu, \"rate_limited\": %zu, "
                "\"unplaced\": %zu, \"gated\": %zu, \"edges\": %zu, \"switched_off\": %zu, "
                "\"aligned\": %s, "
                "\"enu_yaw_rad\": %.4f, \"optimize_ms\": [%.2f, %.2f, %.2f]}",
                s.gnss.fixes, s.gnss.bad_quality, s.gnss.rate_limited, s.gnss.unplaced,
                s.gnss_gated, s.gnss_edges, s.gnss_switched_off, T ? "true" : "false", yaw, gnss[0],
                gnss[1], gnss[2]);
  return out + json;
}

}  // namespace swlio::tools

#include "swlio/daemon/output/map_publisher.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "swlio/core/time.h"
#include "swlio/estimator/map/map_pcd.h"
#include "swlio/ipc/point_cloud.h"

namespace swlio::daemon {
namespace {

double MsSince(int64_t t0_ns) { return static_cast<double>(MonotonicNowNs() - t0_ns) * 1e-6; }

/// Every k-th point, k the smallest that leaves at most max_points.
size_t Thin(size_t max_points, std::vector<Eigen::Vector3f>* points) {
  const size_t k = (points->size() + max_points - 1) / max_points;
  if (k <= 1) return 1;
  size_t kept = 0;
  for (size_t i = 0; i < points->size(); i += k) (*points)[kept++] = (*points)[i];
  points->resize(kept);
  return k;
}

/// The next voxel for `n` points at `voxel_m` when `max_points` are allowed. The count falls as
/// voxel^−k: k = 2 for densely sampled surfaces, less where voxels hold one point each (the
/// 943 m map: k ≈ 0.8). The first step assumes k = 2, which never coarsens more than needed;
/// later ones measure k from the last two builds. 5 % margin, at least ×1.1.
double NextVoxel(
    double voxel_m, size_t n, size_t max_points, double previous_m, size_t previous_n) {
  double k = 2.0;
  if (previous_m > 0.0 && previous_n > n) {
    k = std::clamp(std::log(static_cast<double>(previous_n) / static_cast<double>(n)) /
                       std::log(voxel_m / previous_m),
                   0.5, 3.0);
  }
  const double ratio = static_cast<double>(n) / static_cast<double>(max_points);
  return voxel_m * std::max(1.1, 1.05 * std::pow(ratio, 1.0 / k));
}

/// The merge of a SavedMap (`map` must outlive the function).
MergeFn MergeOf(const estimator::SavedMap& map) {
  return [&map](double voxel_m, const estimator::MergedCloudLimit& limit, std::string* error) {
    return estimator::MergedMapCloud(map, voxel_m, error, limit);
  };
}

}  // namespace

std::optional<MapCloud> BuildMapCloud(const estimator::SavedMap& map,
                                      size_t max_points,
                                      double start_voxel_m,
                                      std::string* error,
                                      const Watchdog::Handle& beat) {
  return BuildMapCloud(MergeOf(map), max_points, start_voxel_m, error, beat);
}

std::optional<MapCloud> BuildMapCloud(const MergeFn& merge,
                                      size_t max_points,
                                      double start_voxel_m,
                                      std::string* error,
                                      const Watchdog::Handle& beat) {
  max_points = std::max<size_t>(max_points, 1);
  MapCloud cloud;
  cloud.voxel_m = std::max(start_voxel_m, estimator::kMergedCloudVoxelM);
  double previous_m = 0.0;
  size_t previous_n = 0;
  for (;;) {
    // A try over the cap keeps only the cap (and counts the rest); the last try keeps every
    // point, to be thinned. The previous try's points go before the next is merged.
    const bool last = cloud.builds >= kMaxVoxelSteps;
    size_t n = 0;
    cloud.points_map = {};
    std::optional<std::vector<Eigen::Vector3f>> points =
        merge(cloud.voxel_m, {last ? std::numeric_limits<size_t>::max() : max_points, &n}, error);
    beat.Beat();
    if (!points) return std::nullopt;
    cloud.points_map = std::move(*points);
    ++cloud.builds;
    if (n <= max_points || last) break;
    const double next_m = NextVoxel(cloud.voxel_m, n, max_points, previous_m, previous_n);
    previous_m = cloud.voxel_m;
    previous_n = n;
    cloud.voxel_m = next_m;
  }
  cloud.keep_every = Thin(max_points, &cloud.points_map);
  return cloud;
}

ipc::PointCloud2 ToPointCloud2(const std::vector<Eigen::Vector3f>& points_map,
                               int64_t t_ns,
                               const std::string& frame_id) {
  ipc::PointCloud2 msg;
  msg.t_ns = t_ns;
  msg.frame_id = frame_id;
  ipc::InitXyzCloud(points_map.size(), /*with_intensity=*/false, &msg);
  for (size_t i = 0; i < points_map.size(); ++i) {
    const Eigen::Vector3f& p = points_map[i];
    ipc::SetPoint(i, {p.x(), p.y(), p.z()}, 0.0f, &msg);
  }
  return msg;
}

MapPublisher::MapPublisher(ipc::Publisher* publisher,
                           std::string frame_id,
                           size_t max_points,
                           double period_s)
    : publisher_(publisher),
      frame_id_(std::move(frame_id)),
      max_points_(std::max<size_t>(max_points, 1)),
      period_ns_(SecToNs(period_s)),
      voxel_m_(estimator::kMergedCloudVoxelM) {}

bool MapPublisher::Publish(const estimator::SavedMap& map,
                           const Watchdog::Handle& beat,
                           double snapshot_ms) {
  return Publish(MergeOf(map), map.nodes.size(), beat, snapshot_ms);
}

bool MapPublisher::Publish(const MergeFn& merge,
                           size_t nodes,
                           const Watchdog::Handle& beat,
                           double snapshot_ms) {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  const int64_t t0 = MonotonicNowNs();
  changed_ = false;
  next_ns_ = t0 + period_ns_;
  std::string error;
  std::optional<MapCloud> cloud = BuildMapCloud(merge, max_points_, voxel_m_, &error, beat);
  last_failed_.store(!cloud, kRelaxed);
  if (!cloud) {
    failures_.fetch_add(1, kRelaxed);
    spdlog::warn("map: not published: {}", error);
    return false;
  }
  voxel_m_ = cloud->voxel_m;
  const size_t keep_every = cloud->keep_every;
  const int64_t stamp_ns = stamps_ != nullptr ? stamps_->ToStamp(t0) : t0;
  const ipc::PointCloud2 msg = ToPointCloud2(cloud->points_map, stamp_ns, frame_id_);
  // The points are in the message now: freed before DDS serializes a third copy of them.
  cloud->points_map = {};
  const double build_ms = snapshot_ms + MsSince(t0);
  // A map only grows, and so does its build: the period stretches to keep the thread's time
  // spent on it under 1 / kPeriodPerBuild (a 943 m drive's map takes ~0.5 s).
  next_ns_ = t0 + std::max(period_ns_, static_cast<int64_t>(build_ms * 1e6 * kPeriodPerBuild));
  const int64_t t1 = MonotonicNowNs();
  const bool ok = publisher_ == nullptr || publisher_->PublishMap(msg);
  const double write_ms = MsSince(t1);
  beat.Beat();
  last_failed_.store(!ok, kRelaxed);
  if (!ok) {
    failures_.fetch_add(1, kRelaxed);
    spdlog::warn("map: DDS refused the map cloud ({} points)", msg.width);
    return false;
  }
  published_.fetch_add(1, kRelaxed);
  points_.store(msg.width, kRelaxed);
  bytes_.store(msg.data.size(), kRelaxed);
  voxel_used_m_.store(voxel_m_, kRelaxed);
  build_ms_.store(build_ms, kRelaxed);
  write_ms_.store(write_ms, kRelaxed);
  spdlog::info(
      "map: {} points from {} nodes (voxel {:.2f} m{}), {:.1f} MB, built in {:.0f} ms, written "
      "in {:.0f} ms",
      msg.width, nodes, voxel_m_,
      keep_every > 1 ? fmt::format(", every {}th point", keep_every) : "",
      static_cast<double>(msg.data.size()) * 1e-6, build_ms, write_ms);
  return true;
}

MapPublishCounters MapPublisher::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  MapPublishCounters c;
  c.enabled = true;
  c.published = published_.load(kRelaxed);
  c.failures = failures_.load(kRelaxed);
  c.last_failed = last_failed_.load(kRelaxed);
  c.points = points_.load(kRelaxed);
  c.bytes = bytes_.load(kRelaxed);
  c.voxel_m = voxel_used_m_.load(kRelaxed);
  c.build_ms = build_ms_.load(kRelaxed);
  c.write_ms = write_ms_.load(kRelaxed);
  return c;
}

}  // namespace swlio::daemon

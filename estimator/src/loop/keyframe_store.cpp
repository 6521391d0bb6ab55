#include "swlio/estimator/loop/keyframe_store.h"

namespace swlio::estimator {
namespace {

std::vector<Eigen::Vector3f> Compact(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back(p.cast<float>());
  return out;
}

std::vector<Eigen::Vector3d> Moved(const Eigen::Isometry3d& T,
                                   const std::vector<Eigen::Vector3f>& points) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const Eigen::Vector3f& p : points) out.push_back(T * p.cast<double>());
  return out;
}

}  // namespace

void KeyframeStore::Add(const KeyframeCloud& keyframe, bool keep_cloud) {
  Cloud& c = clouds_.emplace_back();
  if (!keep_cloud) return;
  c.kept = true;
  c.planes_lidar = Compact(keyframe.planes_lidar);
  c.edges_lidar = Compact(keyframe.edges_lidar);
  c.plane_scores.assign(c.planes_lidar.size(), 0);
  c.edge_scores.assign(c.edges_lidar.size(), 0);
  ++kept_;
  bytes_ += (c.planes_lidar.capacity() + c.edges_lidar.capacity()) * sizeof(Eigen::Vector3f) +
            c.plane_scores.capacity() + c.edge_scores.capacity();
}

std::vector<Eigen::Vector3d> KeyframeStore::Planes(size_t i, const Eigen::Isometry3d& T) const {
  return Moved(T, clouds_[i].planes_lidar);
}

std::vector<Eigen::Vector3d> KeyframeStore::Edges(size_t i, const Eigen::Isometry3d& T) const {
  return Moved(T, clouds_[i].edges_lidar);
}

}  // namespace swlio::estimator

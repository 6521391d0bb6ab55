#include "swlio/estimator/map/merged_cloud_builder.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "swlio/estimator/map/map_pcd.h"

namespace swlio::estimator {

MergedCloudBuilder::MergedCloudBuilder(double voxel_m, size_t max_records, MergedCloudLimit limit)
    : voxel_m_(voxel_m), max_records_(std::max<size_t>(max_records, 1)), limit_(limit) {}

bool MergedCloudBuilder::VoxelOk() const {
  return std::isfinite(voxel_m_) && voxel_m_ >= kMergedCloudMinVoxelM;
}

bool MergedCloudBuilder::NextPass() {
  if (!VoxelOk() || !issue_.empty()) return false;
  if (pass_ == 1) PlanStripes();
  if (pass_ >= 2) ReduceStripe();
  if (pass_ >= 1 && static_cast<size_t>(pass_) > stripes_.size()) return false;
  ++pass_;
  node_ = 0;
  order_ = 0;
  return true;
}

void MergedCloudBuilder::AddPoint(const Eigen::Vector3d& p_map) {
  const uint64_t order = order_++;
  if (!issue_.empty()) return;
  const auto cell = [this](double x) { return static_cast<int64_t>(std::floor(x / voxel_m_)); };
  if (pass_ == 1) {  // check and count
    if (!p_map.allFinite() || p_map.cwiseAbs().maxCoeff() > kMergedCloudMaxCoordinateM) {
      issue_ = "node " + std::to_string(node_) + ": a point in the map frame is not finite or " +
               "beyond " + std::to_string(kMergedCloudMaxCoordinateM) + " m";
      return;
    }
    ++per_x_cell_[cell(p_map.x())];
    return;
  }
  const int64_t x = cell(p_map.x());
  const auto& [first, last] = stripes_[static_cast<size_t>(pass_ - 2)];
  if (x < first || x > last) return;
  points_.push_back({{x, cell(p_map.y()), cell(p_map.z())}, order, p_map});
}

void MergedCloudBuilder::PlanStripes() {
  size_t in_stripe = 0, points = 0;
  for (const auto& [x, n] : per_x_cell_) {
    points += n;
    if (stripes_.empty() || (in_stripe > 0 && in_stripe + n > max_records_)) {
      stripes_.emplace_back(x, x);
      in_stripe = 0;
    }
    stripes_.back().second = x;
    in_stripe += n;
  }
  size_t largest = 0;
  for (const auto& [first, last] : stripes_) {
    size_t n = 0;
    for (auto it = per_x_cell_.find(first); it != per_x_cell_.end() && it->first <= last; ++it)
      n += it->second;
    largest = std::max(largest, n);
  }
  per_x_cell_.clear();
  points_.reserve(largest);
  // A voxel holds at least one point: the centroids are at most the points.
  if (limit_.max_points < points) centroids_.reserve(limit_.max_points);
}

void MergedCloudBuilder::ReduceStripe() {
  std::sort(points_.begin(), points_.end(), [](const CellPoint& a, const CellPoint& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.order < b.order;
  });
  for (size_t begin = 0; begin < points_.size();) {
    size_t end = begin;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    while (end < points_.size() && points_[end].cell == points_[begin].cell) {
      sum += points_[end++].p_map;
    }
    if (centroids_.size() < limit_.max_points) {
      centroids_.push_back((sum / static_cast<double>(end - begin)).cast<float>());
    }
    ++centroids_total_;
    begin = end;
  }
  points_.clear();
}

std::optional<std::vector<Eigen::Vector3f>> MergedCloudBuilder::Finish(std::string* error) {
  const auto refuse = [error](std::string why) {
    if (error != nullptr) *error = "merged cloud: " + std::move(why);
    return std::nullopt;
  };
  if (!VoxelOk()) {
    return refuse("voxel size " + std::to_string(voxel_m_) + " m must be finite and at least " +
                  std::to_string(kMergedCloudMinVoxelM) + " m");
  }
  if (!issue_.empty()) return refuse(issue_);
  if (limit_.total != nullptr) *limit_.total = centroids_total_;
  return std::move(centroids_);
}

}  // namespace swlio::estimator

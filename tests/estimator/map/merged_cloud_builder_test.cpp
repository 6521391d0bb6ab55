// MergedCloudBuilder (merged_cloud_builder.h): the stripes bound the memory and change nothing.
// Every stripe size gives the same cloud, to the last bit, as the reference: one centroid per
// voxel, the voxel's points summed in input order, in voxel order.
#include "swlio/estimator/map/merged_cloud_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace swlio::estimator {
namespace {

struct Node {
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3f> planes, edges;
};

std::vector<Node> RandomNodes(int nodes, int points_each) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  std::vector<Node> out(static_cast<size_t>(nodes));
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].T_map_lidar.translation() = Eigen::Vector3d(0.5 * static_cast<double>(i), 0.1, -0.2);
    out[i].T_map_lidar.linear() =
        Eigen::AngleAxisd(0.1 * static_cast<double>(i), Eigen::Vector3d::UnitZ()).matrix();
    for (int k = 0; k < points_each; ++k) {
      (k % 3 == 0 ? out[i].edges : out[i].planes).emplace_back(u(rng), u(rng), u(rng));
    }
  }
  return out;
}

std::optional<std::vector<Eigen::Vector3f>> Build(const std::vector<Node>& nodes,
                                                  double voxel_m,
                                                  size_t max_records,
                                                  std::string* error,
                                                  int* passes = nullptr,
                                                  MergedCloudLimit limit = {}) {
  MergedCloudBuilder b(voxel_m, max_records, limit);
  while (b.NextPass()) {
    for (const Node& n : nodes) b.AddNode(n.T_map_lidar, n.planes, n.edges);
  }
  if (passes != nullptr) *passes = b.passes();
  return b.Finish(error);
}

std::vector<Eigen::Vector3f> Reference(const std::vector<Node>& nodes, double voxel_m) {
  std::map<std::array<int64_t, 3>, std::pair<Eigen::Vector3d, int>> voxels;
  for (const Node& n : nodes) {
    for (const auto* points : {&n.planes, &n.edges}) {
      for (const Eigen::Vector3f& p : *points) {
        const Eigen::Vector3d q = n.T_map_lidar * p.cast<double>();
        std::array<int64_t, 3> cell{};
        for (Eigen::Index a = 0; a < 3; ++a)
          cell[static_cast<size_t>(a)] = static_cast<int64_t>(std::floor(q[a] / voxel_m));
        auto& [sum, count] = voxels.try_emplace(cell, Eigen::Vector3d::Zero(), 0).first->second;
        sum += q;
        ++count;
      }
    }
  }
  std::vector<Eigen::Vector3f> out;
  for (const auto& [cell, v] : voxels) out.push_back((v.first / v.second).cast<float>());
  return out;
}

TEST(MergedCloudBuilder, EveryStripeSizeGivesTheReferenceCloudToTheLastBit) {
  const std::vector<Node> nodes = RandomNodes(40, 300);
  const std::vector<Eigen::Vector3f> expected = Reference(nodes, 0.5);
  ASSERT_GT(expected.size(), 2000u);
  ASSERT_LT(expected.size(), 12000u);  // voxels do merge points
  int one_stripe = 0, many = 0;
  for (const size_t max_records : {size_t{1} << 30, size_t{1000}, size_t{37}, size_t{1}}) {
    std::string error;
    int passes = 0;
    const auto cloud = Build(nodes, 0.5, max_records, &error, &passes);
    ASSERT_TRUE(cloud.has_value()) << error;
    ASSERT_EQ(cloud->size(), expected.size()) << max_records;
    for (size_t i = 0; i < expected.size(); ++i) {
      ASSERT_EQ((*cloud)[i], expected[i]) << "point " << i << ", stripes of " << max_records;
    }
    if (max_records > 12000) {
      one_stripe = passes;
    } else {
      many = std::max(many, passes);
    }
  }
  EXPECT_EQ(one_stripe, 2);  // the count, then one stripe
  EXPECT_GT(many, 20);       // one x-cell per stripe at the end
}

// A cap keeps the first points of the full cloud, counts them all, and holds no more than the
// cap (reserved once, not grown by doubling).
TEST(MergedCloudBuilder, ACapKeepsTheCloudsFirstPointsAndCountsThemAll) {
  const std::vector<Node> nodes = RandomNodes(40, 300);
  const std::vector<Eigen::Vector3f> expected = Reference(nodes, 0.5);
  for (const size_t cap :
       {size_t{1}, size_t{1000}, expected.size() - 1, expected.size(), expected.size() + 1000}) {
    for (const size_t max_records : {size_t{1} << 30, size_t{37}}) {
      std::string error;
      size_t total = 0;
      const auto cloud = Build(nodes, 0.5, max_records, &error, nullptr, {cap, &total});
      ASSERT_TRUE(cloud.has_value()) << error;
      EXPECT_EQ(total, expected.size()) << "cap " << cap;
      ASSERT_EQ(cloud->size(), std::min(cap, expected.size())) << "cap " << cap;
      if (cap < expected.size()) {
        EXPECT_EQ(cloud->capacity(), cap) << "reserved once";
      }
      for (size_t i = 0; i < cloud->size(); ++i) {
        ASSERT_EQ((*cloud)[i], expected[i]) << "point " << i << ", cap " << cap;
      }
    }
  }
}

TEST(MergedCloudBuilder, RefusesANonFinitePointWithItsNodeAndABadVoxel) {
  std::vector<Node> nodes = RandomNodes(3, 10);
  nodes[1].planes[4].x() = std::numeric_limits<float>::quiet_NaN();
  std::string error;
  EXPECT_FALSE(Build(nodes, 0.5, 1000, &error).has_value());
  EXPECT_NE(error.find("merged cloud: node 1:"), std::string::npos) << error;
  EXPECT_FALSE(Build(RandomNodes(3, 10), 0.0, 1000, &error).has_value());
  EXPECT_NE(error.find("voxel size"), std::string::npos) << error;
}

TEST(MergedCloudBuilder, NoNodesGiveAnEmptyCloud) {
  std::string error;
  const auto cloud = Build({}, 0.1, 1000, &error);
  ASSERT_TRUE(cloud.has_value()) << error;
  EXPECT_TRUE(cloud->empty());
}

}  // namespace
}  // namespace swlio::estimator

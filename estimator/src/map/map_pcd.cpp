#include "swlio/estimator/map/map_pcd.h"

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <system_error>
#include <vector>

#include "swlio/estimator/common/replace_file.h"
#include "swlio/estimator/map/merged_cloud_builder.h"

namespace swlio::estimator {
namespace {

void SetPcdError(std::string* error, std::string message) {
  if (error != nullptr) *error = std::move(message);
}

void WritePcd(std::ostream& out, const std::vector<Eigen::Vector3f>& points) {
  const std::string n = std::to_string(points.size());
  out << "# .PCD v0.7 - Point Cloud Data file format\n"
      << "VERSION 0.7\n"
      << "FIELDS x y z\n"
      << "SIZE 4 4 4\n"
      << "TYPE F F F\n"
      << "COUNT 1 1 1\n"
      << "WIDTH " << n << "\n"
      << "HEIGHT 1\n"
      << "VIEWPOINT 0 0 0 1 0 0 0\n"
      << "POINTS " << n << "\n"
      << "DATA binary\n";
  std::string body;
  body.reserve(points.size() * 12);
  for (const Eigen::Vector3f& p : points) {
    for (int a = 0; a < 3; ++a) {
      const auto bits = std::bit_cast<uint32_t>(p[a]);
      for (int k = 0; k < 4; ++k) body.push_back(static_cast<char>((bits >> (8 * k)) & 0xff));
    }
  }
  out.write(body.data(), static_cast<std::streamsize>(body.size()));
  out.flush();
}

}  // namespace

std::optional<std::vector<Eigen::Vector3f>> MergedMapCloud(const SavedMap& map,
                                                           double voxel_m,
                                                           std::string* error,
                                                           MergedCloudLimit limit) {
  MergedCloudBuilder builder(voxel_m, MergedCloudBuilder::kMaxRecords, limit);
  while (builder.NextPass()) {
    for (const SavedMapNode& node : map.nodes)
      builder.AddNode(node.T_map_imu * node.T_imu_lidar, node.planes_lidar, node.edges_lidar);
  }
  return builder.Finish(error);
}

long WriteMergedPcd(std::ostream& out, const SavedMap& map, double voxel_m, std::string* error) {
  const std::optional<std::vector<Eigen::Vector3f>> centroids = MergedMapCloud(map, voxel_m, error);
  if (!centroids) return -1;
  WritePcd(out, *centroids);
  if (!out) {
    SetPcdError(error, "merged cloud: stream write failed");
    return -1;
  }
  return static_cast<long>(centroids->size());
}

bool SaveMergedPcd(const std::string& path,
                   const SavedMap& map,
                   double voxel_m,
                   std::string* error) {
  return ReplaceFile(
      path, "merged cloud",
      [&](std::ostream& out, std::string* why) {
        return WriteMergedPcd(out, map, voxel_m, why) >= 0;
      },
      error);
}

}  // namespace swlio::estimator

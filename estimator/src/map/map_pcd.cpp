#include "swlio/estimator/map/map_pcd.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <system_error>
#include <vector>

namespace swlio::estimator {
namespace {

struct CellPoint {
  std::array<int64_t, 3> cell;
  Eigen::Vector3d p_map;
};

void SetPcdError(std::string* error, std::string message) {
  if (error != nullptr) *error = std::move(message);
}

// Every feature point in the map frame with its voxel; "" or what is wrong.
std::string Gather(const SavedMap& map, double voxel_m, std::vector<CellPoint>* out) {
  size_t total = 0;
  for (const SavedMapNode& node : map.nodes)
    total += node.planes_lidar.size() + node.edges_lidar.size();
  out->reserve(total);
  for (size_t i = 0; i < map.nodes.size(); ++i) {
    const SavedMapNode& node = map.nodes[i];
    const Eigen::Isometry3d T_map_lidar = node.T_map_imu * node.T_imu_lidar;
    for (const auto* points : {&node.planes_lidar, &node.edges_lidar}) {
      for (const Eigen::Vector3d& p_lidar : *points) {
        const Eigen::Vector3d p_map = T_map_lidar * p_lidar;
        if (!p_map.allFinite() || p_map.cwiseAbs().maxCoeff() > kMergedCloudMaxCoordinateM) {
          return "node " + std::to_string(i) + ": a point in the map frame is not finite or " +
                 "beyond " + std::to_string(kMergedCloudMaxCoordinateM) + " m";
        }
        CellPoint cp{{}, p_map};
        for (size_t a = 0; a < 3; ++a) {
          cp.cell[a] =
              static_cast<int64_t>(std::floor(p_map[static_cast<Eigen::Index>(a)] / voxel_m));
        }
        out->push_back(cp);
      }
    }
  }
  return {};
}

// One centroid per voxel, in voxel order. The stable sort keeps each voxel's points in map
// order, so the sums (and the output) do not depend on the sort's implementation.
std::vector<Eigen::Vector3f> Centroids(std::vector<CellPoint>* points) {
  std::stable_sort(points->begin(), points->end(),
                   [](const CellPoint& a, const CellPoint& b) { return a.cell < b.cell; });
  std::vector<Eigen::Vector3f> centroids;
  for (size_t begin = 0; begin < points->size();) {
    size_t end = begin;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    while (end < points->size() && (*points)[end].cell == (*points)[begin].cell) {
      sum += (*points)[end++].p_map;
    }
    centroids.push_back((sum / static_cast<double>(end - begin)).cast<float>());
    begin = end;
  }
  return centroids;
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
                                                           std::string* error) {
  if (!std::isfinite(voxel_m) || voxel_m < kMergedCloudMinVoxelM) {
    SetPcdError(error, "merged cloud: voxel size " + std::to_string(voxel_m) +
                           " m must be finite and at least " +
                           std::to_string(kMergedCloudMinVoxelM) + " m");
    return std::nullopt;
  }
  std::vector<CellPoint> points;
  const std::string issue = Gather(map, voxel_m, &points);
  if (!issue.empty()) {
    SetPcdError(error, "merged cloud: " + issue);
    return std::nullopt;
  }
  return Centroids(&points);
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
  const std::string tmp = path + ".tmp";
  std::string why;
  bool ok = false;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      SetPcdError(error, "merged cloud: cannot create " + tmp);
      return false;
    }
    ok = WriteMergedPcd(out, map, voxel_m, &why) >= 0;
    out.close();
    if (ok && !out) why = "merged cloud: closing " + tmp + " failed";
    ok = ok && out;
  }
  std::error_code ec;
  if (ok) {
    std::filesystem::rename(tmp, path, ec);
    if (ec) why = "merged cloud: renaming " + tmp + " to " + path + " failed: " + ec.message();
    ok = !ec;
  }
  if (!ok) {
    std::filesystem::remove(tmp, ec);
    SetPcdError(error, why);
  }
  return ok;
}

}  // namespace swlio::estimator

#pragma once
/// @file
/// A saved map merged into one point cloud for people to look at (CloudCompare, pcl_viewer,
/// Open3D): every node's planar and edge features moved into the map frame
/// (p_map = T_map_imu · T_imu_lidar · p_lidar), reduced to one point per voxel (the centroid
/// of the voxel's points), written as a binary PCD v0.7 file:
///
///   # .PCD v0.7 - Point Cloud Data file format
///   VERSION 0.7
///   FIELDS x y z
///   SIZE 4 4 4
///   TYPE F F F
///   COUNT 1 1 1
///   WIDTH <n>
///   HEIGHT 1
///   VIEWPOINT 0 0 0 1 0 0 0
///   POINTS <n>
///   DATA binary
///
/// followed by n × (x y z) float32 little-endian, metres in the map frame. Voxels are cubes of
/// side voxel_m anchored at the map origin; points come out in voxel order (x, then y, then z
/// cell index ascending).

#include <Eigen/Core>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "swlio/estimator/map/merged_cloud_builder.h"
#include "swlio/estimator/map/saved_map.h"

namespace swlio::estimator {

/// Map-frame points must lie within this distance of the origin on each axis (anything
/// beyond is a corrupt pose, not a map).
inline constexpr double kMergedCloudMaxCoordinateM = 1e9;
/// The voxel swlio-run and swliod write the merged cloud with: fine enough to see equipment,
/// a few MB for a substation.
inline constexpr double kMergedCloudVoxelM = 0.1;
/// The smallest voxel side accepted.
inline constexpr double kMergedCloudMinVoxelM = 1e-3;

/// The merged cloud itself (what WriteMergedPcd writes, and what swliod publishes): one
/// centroid per voxel of side voxel_m, map frame, in voxel order. std::nullopt with *error
/// ("merged cloud: ...") when voxel_m is not finite or below kMergedCloudMinVoxelM, or a
/// map-frame point is not finite or beyond kMergedCloudMaxCoordinateM.
/// `limit` caps the centroids kept (merged_cloud_builder.h).
std::optional<std::vector<Eigen::Vector3f>> MergedMapCloud(const SavedMap& map,
                                                           double voxel_m,
                                                           std::string* error,
                                                           MergedCloudLimit limit = {});

/// Writes the merged cloud; the number of points written, or -1 with *error ("merged cloud:
/// ...") when MergedMapCloud refuses or the stream fails.
long WriteMergedPcd(std::ostream& out, const SavedMap& map, double voxel_m, std::string* error);

/// WriteMergedPcd into `path` (through `path` + ".tmp" and a rename).
bool SaveMergedPcd(const std::string& path,
                   const SavedMap& map,
                   double voxel_m,
                   std::string* error);

}  // namespace swlio::estimator

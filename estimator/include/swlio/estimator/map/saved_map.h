#pragma once
/// @file
/// A saved map: the keyframes of a mapping run (optimized pose in the map frame, extrinsic,
/// de-skewed features in their LiDAR frame, place descriptor) in a versioned binary file, so
/// that a later run can localize against it. Full description: estimator/map-format.md.
///
/// Format, version 2 (version 1 is read and converted, see ConvertManualFrameNodes).
/// Little-endian throughout; integers unsigned unless marked i64; floating
/// point is IEEE 754 (f64 = binary64, f32 = binary32). Offsets in bytes.
///
///   offset  size  field
///   0       8     magic, the ASCII bytes "SWLIOMAP" (no terminator)
///   8       4     u32 version = 2 (1: LiDAR frame of the RoboSense manual, converted on reading)
///   12      4     u32 header flags = 0 (no flag is defined; a reader refuses any other value)
///   16      4     u32 descriptor rings R    (≤ 1024)
///   20      4     u32 descriptor sectors S  (≤ 1024; R and S are both 0 or both > 0)
///   24      8     f64 descriptor max range, m
///   32      8     f64 descriptor min range, m  (0 ≤ min < max when R > 0)
///   40      8     f64 descriptor height offset, m
///   48      4     u32 node count N (≤ 10,000,000)
///   52            N nodes, each 128 + 12·(P + E) + 4·R·S bytes:
///     +0    8     i64 t_ns, strictly increasing from node to node
///     +8    56    f64×7 T_map_imu: tx ty tz (m), qx qy qz qw (unit quaternion, |q| within 1e-3
///                 of 1; the reader renormalizes)
///     +64   56    f64×7 T_imu_lidar, same layout
///     +120  4     u32 plane point count P
///     +124  4     u32 edge point count E   (P + E ≤ 1,000,000)
///     +128        P × f32×3 plane points x y z (m, LiDAR frame: the drivers', x forward,
///                 y left, z up), then E × f32×3 edge points
///                 (f32 rounding error ≤ 3.8 µm below 128 m, ≤ 7.6 µm below 256 m)
///     then        R·S × f32 descriptor, row-major (ring by ring)
///   end − 8 8     u64 FNV-1a 64-bit hash (offset basis 0xcbf29ce484222325, prime
///                 0x100000001b3) of every preceding byte of the file
///
/// Every floating-point value is finite. Nothing follows the hash.

#include <Eigen/Geometry>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace swlio::estimator {

/// 2: nodes' features and T_imu_lidar in the drivers' LiDAR frame (x forward, y left, z up;
/// lidar_decoder.h). 1 (before issue 32): in the RoboSense manual's frame (y forward, x right).
inline constexpr uint32_t kSavedMapVersion = 2;
inline constexpr uint32_t kSavedMapVersionManualFrame = 1;

/// One keyframe of the map.
struct SavedMapNode {
  int64_t t_ns = 0;  ///< keyframe time (host clock of the mapping run)
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();    ///< optimized, map frame
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();  ///< extrinsic at the time
  std::vector<Eigen::Vector3d> planes_lidar;  ///< de-skewed planar features, LiDAR frame, m
  std::vector<Eigen::Vector3d> edges_lidar;   ///< edge features, LiDAR frame, m
  /// Place descriptor: descriptor_rings × descriptor_sectors values, row-major (ring by ring).
  /// Empty exactly when the map's descriptor dimensions are 0.
  std::vector<float> descriptor;
};

struct SavedMap {
  /// The version of the file it was read from (kSavedMapVersion for a map made in memory); a
  /// version-1 map has been converted into the current LiDAR frame.
  uint32_t file_version = kSavedMapVersion;
  /// How the descriptors were made, so that a loader can build compatible query descriptors.
  int descriptor_rings = 0;
  int descriptor_sectors = 0;
  double descriptor_max_range_m = 0.0;
  double descriptor_min_range_m = 0.0;
  double descriptor_height_offset_m = 0.0;
  std::vector<SavedMapNode> nodes;  ///< in strictly increasing t_ns
};

/// Format limits (a reader refuses larger values before allocating anything for them).
inline constexpr uint32_t kSavedMapMaxNodes = 10'000'000;
inline constexpr uint32_t kSavedMapMaxPointsPerNode = 1'000'000;  ///< planes + edges
inline constexpr uint32_t kSavedMapMaxDescriptorDim = 1024;       ///< rings, sectors each
/// A stored quaternion's norm may differ from 1 by this much (it is then renormalized).
inline constexpr double kSavedMapQuaternionTolerance = 1e-3;

/// Turns version-1 nodes into version 2's frame: each feature p ← Rz(−90°)·p, i.e. (x, y, z) ←
/// (y, −x, z), and T_imu_lidar ← T_imu_lidar·Rz(+90°). Exact in float (a quarter turn only swaps
/// and negates coordinates), and every feature stays where it was in the map frame
/// (T_map_imu · T_imu_lidar · p unchanged), so localization in an old map works as before.
void ConvertManualFrameNodes(SavedMap* map);

/// Writes the binary format above (version kSavedMapVersion whatever `file_version` says).
/// Checks the whole map first and writes nothing when it is
/// invalid: non-finite values (or points beyond float range), a rotation that is not one
/// (‖RᵀR − I‖ > 1e-6 or det R < 0), descriptor sizes other than rings × sectors, dimensions
/// or counts beyond the limits, t_ns not strictly increasing. Then false with *error set
/// ("map write: ..."); false too when the stream fails.
bool WriteSavedMap(std::ostream& out, const SavedMap& map, std::string* error);

/// Reads the whole stream and validates it. std::nullopt with *error ("map file: ...") on any
/// malformation: bad magic, unsupported version or flags, truncated data, counts beyond the
/// limits or larger than the remaining bytes allow, trailing bytes, checksum mismatch,
/// non-finite numbers, a non-unit quaternion, nodes not in strictly increasing t_ns.
/// Memory grows with the bytes actually read, never with a count read from the stream.
std::optional<SavedMap> ReadSavedMap(std::istream& in, std::string* error);

/// Writes `path` + ".tmp", flushes it to disk, then renames it over `path`: a crash leaves
/// either the old file or the complete new one. The temporary file is removed on failure.
bool SaveMapFile(const std::string& path, const SavedMap& map, std::string* error);

/// Reads a regular file with ReadSavedMap; errors read "map file <path>: ...".
std::optional<SavedMap> LoadMapFile(const std::string& path, std::string* error);

}  // namespace swlio::estimator

#pragma once
/// @file
/// Trajectories for evaluation and their file formats.
///
/// - TUM RGB-D format (https://cvg.cit.tum.de/data/datasets/rgbd-dataset/file_formats):
///   one pose per line, `timestamp tx ty tz qx qy qz qw` (seconds, metres, Hamilton quaternion
///   with w last); lines starting with `#` are comments. As evo does, the quaternion is
///   normalised when it is turned into a rotation matrix.
/// - KITTI odometry format (devkit readme, "poses/XX.txt"): one pose per line, the first three
///   rows of the 4×4 matrix T_world_cam row-major (12 numbers). The rotation block is kept
///   exactly as read (not re-orthonormalised), as evo does. An optional timestamp file
///   (KITTI "times.txt") has one time in seconds per line.
///
/// Poses are stored as 4×4 homogeneous matrices T_world_body.

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace swlio::eval {

/// Every failure of the evaluation library (malformed file, too few poses, degenerate input).
class EvalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Pose = Eigen::Matrix4d;

struct Trajectory {
  std::vector<double> stamps_s;  ///< one per pose, or empty when the file had no times
  std::vector<Pose> poses;       ///< T_world_body

  std::size_t Size() const { return poses.size(); }
  bool HasStamps() const { return !stamps_s.empty(); }
  Eigen::Vector3d Position(std::size_t i) const { return poses[i].block<3, 1>(0, 3); }
  /// Keeps only the poses (and stamps) at `ids`, in that order; ids may repeat.
  Trajectory Select(const std::vector<std::size_t>& ids) const;
  /// Sum of the distances between consecutive positions (metres).
  double PathLength() const;
};

/// Rotation matrix of the normalised quaternion (w, x, y, z); throws on a zero quaternion.
Eigen::Matrix3d RotationFromQuaternion(double w, double x, double y, double z);

/// Parses TUM text; `name` prefixes error messages ("name:line: ...").
Trajectory ParseTum(std::istream& in, const std::string& name);
/// Parses KITTI poses (no stamps).
Trajectory ParseKitti(std::istream& in, const std::string& name);
/// Parses a KITTI timestamp file: one number (seconds) per line.
std::vector<double> ParseTimes(std::istream& in, const std::string& name);

Trajectory ReadTumFile(const std::filesystem::path& path);
/// Reads KITTI poses; when `times_path` is not empty, attaches its stamps (counts must match).
Trajectory ReadKittiFile(const std::filesystem::path& path,
                         const std::filesystem::path& times_path = {});

/// Writes TUM text with full double precision (for tests and tools).
void WriteTum(std::ostream& out, const Trajectory& trajectory);
/// Writes KITTI text with full double precision.
void WriteKitti(std::ostream& out, const Trajectory& trajectory);

}  // namespace swlio::eval

#pragma once
/// @file
/// De-skew: every point of a sweep is moved into the LiDAR frame at the sweep's end, using the
/// IMU-propagated pose at the point's own time.
///
/// The paper interpolates linearly between the poses at the sweep's two ends (§3, Fig. 1); here
/// the pose track holds one pose per IMU sample (400 Hz, 40 per sweep), and each point's pose
/// is interpolated between the two samples around its time (linear in translation, geodesic in
/// rotation), so turns that change rate within a sweep are followed. Points fired within 20 µs
/// of each other share one interpolated transform (< 0.7 mm at 30 m, 1.5 m/s, 60 °/s).
///
///   p_end = (T_world_imu(t_end) · T_imu_lidar)⁻¹ · T_world_imu(t_i) · T_imu_lidar · p_i

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

#include "swlio/core/types.h"

namespace swlio::estimator {

/// Time-ordered IMU poses with interpolation.
class PoseTrack {
 public:
  void Clear() { samples_.clear(); }
  /// Appends a pose; times must increase.
  void Add(int64_t t_ns, const Eigen::Isometry3d& T_world_imu);
  /// Pose at t by interpolation; false when t lies outside the track.
  bool At(int64_t t_ns, Eigen::Isometry3d* T_world_imu) const;
  /// The same, and false too when t falls strictly between two poses more than `max_gap_ns`
  /// apart (a pose exactly at t is always taken).
  bool At(int64_t t_ns, int64_t max_gap_ns, Eigen::Isometry3d* T_world_imu) const;
  /// Forgets the poses before `t_ns` (a track kept over a sliding time window).
  void DropBefore(int64_t t_ns);
  bool empty() const { return samples_.empty(); }
  int64_t begin_ns() const { return samples_.front().t_ns; }
  int64_t end_ns() const { return samples_.back().t_ns; }

 private:
  struct Sample {
    int64_t t_ns;
    Eigen::Quaterniond q;
    Eigen::Vector3d p;
    /// The geodesic to the next sample's rotation, as Eigen's slerp computes it: the dot
    /// product of the two quaternions, the angle acos|dot| and its sine (set when the next
    /// sample is added). A de-skew interpolates thousands of times between the same ~40
    /// samples; these three cost an acos and a sin each time.
    double dot_next = 1.0;
    double theta_next = 0.0;
    double sin_theta_next = 0.0;
  };
  /// `a.q.slerp(u, b.q)` to the last bit, from `a`'s kept terms (b follows a).
  static Eigen::Quaterniond Slerp(const Sample& a, const Sample& b, double u);
  /// The two samples around t (t inside the track, which is not empty); the second may equal t.
  std::pair<const Sample*, const Sample*> Around(int64_t t_ns) const;
  std::vector<Sample> samples_;
};

struct DeskewResult {
  size_t points = 0;     ///< points written
  size_t uncovered = 0;  ///< points whose time the track does not cover (left as measured)
};

/// De-skews `scan` (host times) into the LiDAR frame at `scan.t_end_ns`. `out` is resized.
DeskewResult Deskew(const Scan& scan,
                    const PoseTrack& track,
                    const Eigen::Isometry3d& T_imu_lidar,
                    std::vector<Eigen::Vector3d>* out);

/// The same into a whole scan: `out` becomes `scan` with every point's `xyz_m` de-skewed (the
/// double result rounded to float), in one pass and, once `out` has the capacity, without
/// allocation. `out` must not be `&scan`.
DeskewResult DeskewScan(const Scan& scan,
                        const PoseTrack& track,
                        const Eigen::Isometry3d& T_imu_lidar,
                        Scan* out);

}  // namespace swlio::estimator
